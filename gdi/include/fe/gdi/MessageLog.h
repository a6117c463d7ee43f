// Layer 2 (GDI abstraction): the validation layer's and GL debug output's messages, each printed
// once (a per-frame mistake would otherwise print the same long line every frame), with how
// often each repeated printed when the device is destroyed. Both backends report through one.
#pragma once
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <string_view>

namespace fe::gdi {

class MessageLog {
public:
    explicit MessageLog(std::string source) : source_(std::move(source)) {}
    MessageLog(const MessageLog&) = delete;
    MessageLog& operator=(const MessageLog&) = delete;
    ~MessageLog() { printRepeats(); }

    // Prints "<source> <severity>: <message>" to stderr the first time this exact message is
    // seen, and counts every time. Thread-safe (drivers call back from their own threads).
    void report(std::string_view severity, std::string_view message);
    // How often a message was reported (0: never), and how many distinct messages there were.
    uint64_t count(std::string_view severity, std::string_view message) const;
    size_t distinct() const;
    // The messages reported more than once, with their counts (also run at destruction).
    void printRepeats();

private:
    std::string source_;
    mutable std::mutex mutex_;
    std::map<std::string, uint64_t, std::less<>> counts_;  // "<severity>: <message>"
    bool printed_ = false;
};

}  // namespace fe::gdi
