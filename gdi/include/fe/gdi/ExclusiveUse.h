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
#include <shared_mutex>
#include <span>
#include <vector>

#include "fe/gdi/Device.h"

namespace fe::gdi {

// A process-wide lock for a native layer whose own global state is not thread-safe across
// devices. Vulkan's validation layer 1.3.239 (Debian 12) keeps every device's data in one map
// that it changes, unlocked, when a device or instance is made or destroyed and reads in every
// call (KhronosGroup/Vulkan-ValidationLayers#4391): a device made or destroyed on one thread
// while another thread's device works crashed inside the layer (examples/materials under ASan).
// Calls hold it shared, re-entrantly on one thread; making or destroying a device holds it
// alone. Taken only where the layer is loaded, so a device without validation pays nothing.
class NativeLayerLock {
public:
    // Around every call into a device or list: shared, nesting on one thread counted.
    class Call {
    public:
        explicit Call(bool active);
        ~Call();
        Call(const Call&) = delete;
        Call& operator=(const Call&) = delete;

    private:
        bool active_;
    };
    // Around making and destroying a device: exclusive. On a thread already inside a call (a
    // device made from a callback) it is not taken, since waiting there would wait on itself.
    class Change {
    public:
        explicit Change(bool active);
        ~Change();
        Change(const Change&) = delete;
        Change& operator=(const Change&) = delete;

    private:
        bool active_;
    };
};

// `list` behind the check: each call claims it for its duration (and, with `layerLock`, holds
// NativeLayerLock::Call too).
std::unique_ptr<CommandList> exclusiveUse(std::unique_ptr<CommandList> list,
                                          bool layerLock = false);

// For Device::submit and CommandList::executeSecondary: checks the array (no null, no list
// twice), claims every checked list for the lifetime of this object (an Error names the one
// another thread is using, and nothing stays claimed), and gives the lists behind the checks;
// lists without one pass through. `self`, the list whose executeSecondary this is (already
// claimed by its own call), passes through unclaimed so that the backend refuses it as itself.
class ClaimedLists {
public:
    ClaimedLists(std::span<CommandList* const> lists, const char* what,
                 const CommandList* self = nullptr);
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
