// Layer 2 (GDI abstraction): "one thread per command list at a time", checked. A list is not
// thread-safe (Vulkan's command buffers are externally synchronised; the GL stream has one
// cursor), so two threads calling one list at once corrupt it. With DeviceCreateDesc::validation
// every backend hands out its lists behind this check, and a call that finds the list in use by
// another thread throws the same Error on every backend before touching the list; the thread
// already inside goes on undisturbed. Without validation the check is absent and such a use is
// undefined, as Vulkan's is without its layer: always on, this check measured 62 more
// instructions a draw in callgrind (Vulkan's abstraction overhead 80 -> 142, 4.9 % -> 8.7 % of
// the direct path; the criterion is 5 %).
//
//   list = gdi::exclusiveUse(std::make_unique<BackendList>(...));   // createCommandList
//   gdi::ClaimedLists claimed(lists, "submit");                       // Device::submit
//   for (CommandList* l : claimed.lists()) ... the backend's own lists, held until the end
#pragma once
#include <atomic>
#include <memory>
#include <span>
#include <vector>

#include "fe/gdi/Device.h"

namespace fe::gdi {

// `list` behind the check: each call claims it for its duration.
std::unique_ptr<CommandList> exclusiveUse(std::unique_ptr<CommandList> list);

// For Device::submit and CommandList::executeSecondary: checks the array (no null, no list
// twice), claims every checked list for the lifetime of this object (an Error names the one
// another thread is using, and nothing stays claimed), and gives the lists behind the checks;
// lists without one pass through. `self`, the list whose executeSecondary this is (already
// claimed by its own call), passes through unclaimed so that the backend refuses it as itself.
class ClaimedLists {
public:
    ClaimedLists(std::span<CommandList* const> lists, const char* what, const CommandList* self = nullptr);
    ~ClaimedLists();
    ClaimedLists(const ClaimedLists&) = delete;
    ClaimedLists& operator=(const ClaimedLists&) = delete;
    std::span<CommandList* const> lists() const { return inner_; }

private:
    void release();
    std::vector<CommandList*> inner_;
    std::vector<std::atomic<bool>*> held_;
};

}  // namespace fe::gdi
