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

void wrongQueue(QueueKind list, QueueKind needs, const char* what) {
    const std::string queue = queueKindName(list);
    const std::string runs = list == QueueKind::Copy
                                 ? "copies, clearBuffer, barriers and debug groups only"
                                 : "no render passes, generateMips or resolveTexture";
    throw Error(std::string(what) + ": this list is for the " + queue + " queue, which runs " +
                runs + " (make the list with CommandListDesc{.queue = QueueKind::" +
                (needs == QueueKind::Graphics ? "Graphics" : "Compute") + "})");
}

QueueKind submissionQueue(std::span<CommandList* const> lists, const SubmitDesc& desc,
                          FenceValue lastIssued) {
    if (desc.waitFor > lastIssued)
        throw Error("submit: SubmitDesc::waitFor is fence " + std::to_string(desc.waitFor) +
                    ", which was never issued (the last submission's is " +
                    std::to_string(lastIssued) + ")");
    if (lists.empty()) return QueueKind::Graphics;
    const QueueKind queue = lists[0]->queue();
    for (size_t i = 1; i < lists.size(); ++i)
        if (lists[i]->queue() != queue)
            throw Error("submit: list 0 is for the " + std::string(queueKindName(queue)) +
                        " queue and list " + std::to_string(i) + " for the " +
                        queueKindName(lists[i]->queue()) +
                        " queue (one submission goes to one queue)");
    return queue;
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
