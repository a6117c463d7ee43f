#include "fe/gdi/MessageLog.h"

#include <iostream>

namespace fe::gdi {

namespace {
std::string key(std::string_view severity, std::string_view message) {
    std::string k(severity);
    k += ": ";
    k += message;
    return k;
}
}  // namespace

void MessageLog::report(std::string_view severity, std::string_view message) {
    std::string k = key(severity, message);
    std::lock_guard lock(mutex_);
    auto [it, first] = counts_.try_emplace(std::move(k), 0);
    if (++it->second == 1) std::cerr << source_ << " " << it->first << "\n";
    printed_ = false;
}

uint64_t MessageLog::count(std::string_view severity, std::string_view message) const {
    std::lock_guard lock(mutex_);
    auto it = counts_.find(key(severity, message));
    return it == counts_.end() ? 0 : it->second;
}

size_t MessageLog::distinct() const {
    std::lock_guard lock(mutex_);
    return counts_.size();
}

void MessageLog::printRepeats() {
    std::lock_guard lock(mutex_);
    if (printed_) return;
    printed_ = true;
    for (const auto& [message, n] : counts_) {
        if (n < 2) continue;
        constexpr size_t kShown = 160;  // the whole text was printed the first time
        std::cerr << source_ << " message repeated " << n << " times in all: "
                  << (message.size() > kShown ? message.substr(0, kShown) + "..." : message)
                  << "\n";
    }
}

}  // namespace fe::gdi
