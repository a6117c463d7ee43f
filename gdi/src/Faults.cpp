#include "fe/gdi/Faults.h"

#include <array>
#include <atomic>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <mutex>
#include <vector>

namespace fe::gdi::fault {

namespace {

struct Counter {
    explicit Counter(uint64_t n) : remaining(n) {}
    std::atomic<uint64_t> remaining;  // calls until the failing one; 0: disarmed
    std::atomic<uint64_t> fired{0};
    std::atomic<uint64_t> calls{0};
};

const char* const kSiteNames[] = {"allocation", "submission"};

// FE_FAULT_TRACE: the calls in order, written when the process exits (normally or by exit()).
class Trace {
public:
    Trace() {
        const char* f = std::getenv("FE_FAULT_TRACE");
        if (f && *f) path_ = f;
    }
    ~Trace() {
        if (path_.empty()) return;
        std::ofstream out(path_);
        for (const auto& [site, ordinal, call, object] : lines_)
            out << kSiteNames[size_t(site)] << ' ' << ordinal << ' ' << call
                << (object.empty() ? "" : " @") << object << '\n';
    }
    void record(Site site, uint64_t ordinal, const char* call, const char* object) {
        if (path_.empty()) return;
        std::lock_guard lock(mutex_);
        lines_.push_back({site, ordinal, call, object ? object : ""});
    }

private:
    struct Line {
        Site site;
        uint64_t ordinal;
        const char* call;
        std::string object;  // copied: the name may not outlive the call
    };
    std::string path_;
    std::mutex mutex_;
    std::vector<Line> lines_;
};

Trace& trace() {
    static Trace t;
    return t;
}

uint64_t fromEnvironment(const char* name, const char* what) {
    const char* text = std::getenv(name);
    if (!text || !*text) return 0;
    char* end = nullptr;
    const unsigned long long n = std::strtoull(text, &end, 10);
    if (*end || n == 0 || text[0] == '-')
        throw Error(std::string(name) + " must be a positive integer (the N-th native " + what +
                    " fails), got '" + text + "'");
    std::cerr << "fe: fault injection: native " << what << " number " << n << " will fail (" << name
              << ")\n";
    return n;
}

// Read from the environment on first use; a bad value is an error at every use until fixed.
std::array<Counter, 2>& counters() {
    static std::array<Counter, 2> c{Counter(fromEnvironment("FE_FAULT_ALLOC", "allocation")),
                                    Counter(fromEnvironment("FE_FAULT_SUBMIT", "submission"))};
    return c;
}

thread_local const char* currentObject = nullptr;  // ObjectScope

}  // namespace

ObjectScope::ObjectScope(const char* name) : previous_(currentObject) { currentObject = name; }

ObjectScope::~ObjectScope() { currentObject = previous_; }

void arm(Site site, uint64_t n) { counters()[size_t(site)].remaining = n; }

bool hit(Site site, const char* call) {
    Counter& c = counters()[size_t(site)];
    trace().record(site, ++c.calls, call, currentObject);
    uint64_t r = c.remaining.load(std::memory_order_relaxed);
    while (r != 0) {
        if (c.remaining.compare_exchange_weak(r, r - 1)) {
            if (r != 1) return false;
            c.fired++;
            std::cerr << "fe: fault injection: native " << kSiteNames[size_t(site)] << " "
                      << c.calls << " (" << call << ") fails\n";
            return true;
        }
    }
    return false;
}

uint64_t fired(Site site) { return counters()[size_t(site)].fired; }

uint64_t calls(Site site) { return counters()[size_t(site)].calls; }

}  // namespace fe::gdi::fault

namespace fe::gdi {

std::string describeObject(const char* kind, const std::string& name, const std::string& detail) {
    return std::string(kind) + (name.empty() ? "" : " '" + name + "'") +
           (detail.empty() ? "" : " (" + detail + ")");
}

std::string toString(const LiveObjects& o) {
    return "{buffers " + std::to_string(o.buffers) + ", textures " + std::to_string(o.textures) +
           ", samplers " + std::to_string(o.samplers) + ", shaders " + std::to_string(o.shaders) +
           ", pipelines " + std::to_string(o.pipelines) + ", timers " + std::to_string(o.timers) +
           ", heaps " + std::to_string(o.heaps) + ", native objects " +
           std::to_string(o.nativeObjects) + "}";
}

bool leakCheckEnabled() {
    static const bool enabled = [] {
        const char* v = std::getenv("FE_LEAK_CHECK");
        return v && std::string(v) == "1";
    }();
    return enabled;
}

void reportLeaksAtDestruction(const std::string& backend, const LiveObjects& live,
                              const std::vector<std::string>& named) {
    if (live == LiveObjects{}) return;
    std::string names;
    for (const auto& n : named) names += (names.empty() ? ": " : ", ") + n;
    std::cerr << "fe leak check: " << backend << " device destroyed with " << toString(live)
              << " still alive" << names << "\n";
}

DeviceLostError DeviceLoss::lose(const std::string& backend, const std::string& cause) {
    std::lock_guard lock(mutex_);
    if (!lost_.load(std::memory_order_relaxed)) {
        backend_ = backend;
        cause_ = cause;
        lost_.store(true, std::memory_order_release);
    }
    return DeviceLostError(backend + ": device lost: " + cause);
}

void DeviceLoss::throwLost(const char* call) const {
    std::lock_guard lock(mutex_);
    throw DeviceLostError(backend_ + ": " + call + ": device lost (" + cause_ +
                          "); nothing more runs on this device");
}

}  // namespace fe::gdi
