// Layer 4 (GDI isolation): choosing a backend at startup. The only place that knows every backend.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "fe/gdi/Device.h"

namespace fe::gdi {

struct DeviceCreateDesc {
    std::string backend = "auto";  // auto | vulkan | gl | gl-egl | gl-osmesa | gl-glfw
    bool validation = false;       // Khronos validation layer / GL debug context
    bool verbose = true;           // auto: say which backend was picked and why others were not
};

// Concrete backends in the order `auto` tries them.
const std::vector<std::string>& backendNames();
// Every accepted --backend value, for error messages.
std::string validBackendList();

struct BackendProbe {
    std::string name;
    bool available = false;
    std::string reason;  // why not, when unavailable
    std::unique_ptr<Device> device;
};

// Starts one named concrete backend; never throws: failure is reported in `reason`.
BackendProbe probeBackend(const std::string& name, bool validation);

// Resolves auto / gl / FE_BACKEND and starts the first backend that works. Throws Error listing
// the valid names for an unknown name, and why each candidate failed when none starts.
std::unique_ptr<Device> createDevice(const DeviceCreateDesc& desc);

// Expands "all" into the concrete backends, checks names; throws Error for unknown ones.
std::vector<std::string> expandBackendList(const std::string& nameOrAll);

}  // namespace fe::gdi
