// Shared validation: Submission: the lists handed to submit, fences, and objects destroyed before their use ran.
#include "ValidationSupport.h"

namespace fe::gdi::validate {

void listOfDestroyedDevice(const char* what) {
    throw Error(
        std::string(what) +
        ": the device of this command list was destroyed (destroy lists before their device)");
}

void fenceNotIssued(FenceValue fence, FenceValue last, const char* what) {
    throw Error(std::string(what) + ": fence " + std::to_string(fence) +
                " was never issued (the last submission's is " + std::to_string(last) + ")");
}

void submittedLists(std::span<CommandList* const> lists) {
    for (size_t i = 0; i < lists.size(); ++i) {
        if (!lists[i]) throw Error("submit: list " + std::to_string(i) + " is null");
        for (size_t j = 0; j < i; ++j)
            if (lists[j] == lists[i])
                throw Error("submit: the same list at " + std::to_string(j) + " and " +
                            std::to_string(i) + " (a recording runs once)");
    }
}

void destroyedBeforeSubmit(const char* kind, uint32_t id) {
    throw Error(
        std::string("submit: the list uses ") + kind + " handle " + std::to_string(id) +
        ", destroyed after it was recorded; record the work again in a new command list (this one keeps "
        "its refused recording)");
}

void secondaryOfAnotherDevice(size_t index) {
    throw Error("executeSecondary: list " + std::to_string(index) + " belongs to another device");
}

}  // namespace fe::gdi::validate
