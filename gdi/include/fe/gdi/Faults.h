// Native API failures, for the backends (layer 3 helpers; nothing above layer 4 includes this):
// test-only fault injection, and the lost state of a device.
//
// Fault injection makes the N-th native allocation or submission fail the way the driver
// reports a real failure, so every backend's error paths run on any machine:
//   FE_FAULT_ALLOC=N   the N-th native allocation reports out of memory. Vulkan: every
//                      vkCreate* and vkAllocate* call of the device, vkMapMemory and
//                      vkBegin/EndCommandBuffer (VK_ERROR_OUT_OF_DEVICE_MEMORY); GL: the
//                      storage calls glNamedBufferStorage and glTextureStorage* (GL_OUT_OF_MEMORY).
//   FE_FAULT_SUBMIT=N  the N-th native submission reports a lost device: Vulkan vkQueueSubmit
//                      (Device::submit, the blocking transfers' own submissions, the swap chain)
//                      and vkQueuePresentKHR (VK_ERROR_DEVICE_LOST); GL Device::submit and
//                      present (a context reset, as glGetGraphicsResetStatus reports one).
//   FE_FAULT_TRACE=FILE  at exit, every native call of either kind made, one line each:
//                      "allocation|submission ORDINAL CALL[ @OBJECT]" (the fault sweep picks its
//                      targets from it); OBJECT: the debug name of the object being created.
// Only the N-th call fails. Counting is per process from its first native call; fault::arm
// restarts it from the moment of the call (gtests).
#pragma once
#include <atomic>
#include <mutex>
#include <cstdint>
#include <string>
#include <vector>

#include "fe/gdi/Device.h"

namespace fe::gdi::fault {

enum class Site : uint8_t { Allocation, Submission };

// The n-th native call of `site` from now on fails; n = 0: none does.
void arm(Site site, uint64_t n);
// The native call `call` (its API name, a string literal) of `site` is about to be made: true
// when it is the one to fail (the caller then skips the call and takes the driver's failure
// result instead).
bool hit(Site site, const char* call);
// Native calls of `site` made so far (counted whether or not armed).
uint64_t calls(Site site);
// Failures injected at `site` so far.
uint64_t fired(Site site);

// While one lives, this thread's native calls are made for the object `name` (a desc's debug
// name; null: unnamed): FE_FAULT_TRACE's lines say so, so the fault sweep can tell apart two
// runs that make the same API calls for different objects. Costs a pointer swap.
class ObjectScope {
public:
    explicit ObjectScope(const char* name);
    ~ObjectScope();
    ObjectScope(const ObjectScope&) = delete;
    ObjectScope& operator=(const ObjectScope&) = delete;

private:
    const char* previous_;
};

}  // namespace fe::gdi::fault

namespace fe::gdi {

// Whether a device is lost. Device entry points that create, transfer, submit or wait call
// check() first; the per-draw recording path does not (see Device.h, Errors).
// How errors name an object: "texture 'albedo' (64x64 RGBA8)", "buffer (256 bytes)" when unnamed.
std::string describeObject(const char* kind, const std::string& name, const std::string& detail);

// FE_LEAK_CHECK=1 (device destructors): whether to report, and the report of `live` on stderr,
// naming the buffers and textures left (`named`), unless nothing is left.
bool leakCheckEnabled();
void reportLeaksAtDestruction(const std::string& backend, const LiveObjects& live,
                              const std::vector<std::string>& named);
std::string toString(const LiveObjects& live);

// Thread-safe: any thread may check while another (a GL context thread) marks the loss.
class DeviceLoss {
public:
    bool lost() const { return lost_.load(std::memory_order_acquire); }
    void check(const char* call) const {
        if (lost()) [[unlikely]]
            throwLost(call);
    }
    // Marks the device lost (the first cause is kept) and returns the error to throw now.
    DeviceLostError lose(const std::string& backend, const std::string& cause);

private:
    [[noreturn, gnu::cold]] void throwLost(const char* call) const;
    mutable std::mutex mutex_;
    std::string backend_, cause_;  // written once, under mutex_, before lost_
    std::atomic<bool> lost_{false};
};

}  // namespace fe::gdi
