// Layer 3 (backends' shared plumbing): the command lists a device has made and not yet
// destroyed. A device destroyed before its lists orphans them: each releases what it holds of
// the device at once, and afterwards destroying it touches nothing and recording into it throws
// Error ("the device of this command list was destroyed") instead of using freed memory.
#pragma once
#include <mutex>
#include <unordered_set>

namespace fe::gdi {

template <class List>
class LiveLists {
public:
    void add(List* list) {
        std::lock_guard lock(mutex_);
        lists_.insert(list);
    }
    void remove(List* list) {
        std::lock_guard lock(mutex_);
        lists_.erase(list);
    }
    // The device's destructor, first: every list still alive lets go of it.
    void orphanAll() {
        std::lock_guard lock(mutex_);
        for (List* list : lists_) list->orphan();
        lists_.clear();
    }

private:
    std::mutex mutex_;
    std::unordered_set<List*> lists_;
};

}  // namespace fe::gdi
