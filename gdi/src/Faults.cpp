#include "fe/gdi/Faults.h"

#include <array>
#include <atomic>
#include <cstdlib>
#include <iostream>

namespace fe::gdi::fault {

namespace {

struct Counter {
    explicit Counter(uint64_t n) : remaining(n) {}
    std::atomic<uint64_t> remaining;  // calls until the failing one; 0: disarmed
    std::atomic<uint64_t> fired{0};
};

uint64_t fromEnvironment(const char* name, const char* what) {
    const char* text = std::getenv(name);
    if (!text || !*text) return 0;
    char* end = nullptr;
    const unsigned long long n = std::strtoull(text, &end, 10);
    if (*end || n == 0 || text[0] == '-')
        throw Error(std::string(name) + " must be a positive integer (the N-th native " + what + " fails), got '" + text + "'");
    std::cerr << "fe: fault injection: native " << what << " number " << n << " will fail (" << name << ")\n";
    return n;
}

// Read from the environment on first use; a bad value is an error at every use until fixed.
std::array<Counter, 2>& counters() {
    static std::array<Counter, 2> c{Counter(fromEnvironment("FE_FAULT_ALLOC", "allocation")),
                                    Counter(fromEnvironment("FE_FAULT_SUBMIT", "submission"))};
    return c;
}

}  // namespace

void arm(Site site, uint64_t n) { counters()[size_t(site)].remaining = n; }

bool hit(Site site) {
    Counter& c = counters()[size_t(site)];
    uint64_t r = c.remaining.load(std::memory_order_relaxed);
    while (r != 0) {
        if (c.remaining.compare_exchange_weak(r, r - 1)) {
            if (r != 1) return false;
            c.fired++;
            return true;
        }
    }
    return false;
}

uint64_t fired(Site site) { return counters()[size_t(site)].fired; }

}  // namespace fe::gdi::fault

namespace fe::gdi {

std::string describeObject(const char* kind, const std::string& name, const std::string& detail) {
    return std::string(kind) + (name.empty() ? "" : " '" + name + "'") + (detail.empty() ? "" : " (" + detail + ")");
}

DeviceLostError DeviceLoss::lose(const std::string& backend, const std::string& cause) {
    if (cause_.empty()) {
        backend_ = backend;
        cause_ = cause;
    }
    return DeviceLostError(backend + ": device lost: " + cause);
}

void DeviceLoss::throwLost(const char* call) const {
    throw DeviceLostError(backend_ + ": " + call + ": device lost (" + cause_ + "); nothing more runs on this device");
}

}  // namespace fe::gdi
