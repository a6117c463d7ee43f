// Shared validation: Query sets and timers: descriptions, the recording rules (QueryRecording) and read-backs.
#include "ValidationSupport.h"

namespace fe::gdi::validate {

namespace {

std::string queryName(const std::string& set, uint32_t index) {
    return "query " + std::to_string(index) + " of set '" + set + "'";
}

void queryIndex(const QuerySetDesc& d, const std::string& name, uint32_t index, const char* what) {
    if (index >= d.count)
        fail(what, queryName(name, index) + " is out of range (the set has " +
                       std::to_string(d.count) + ")");
}

}  // namespace

void querySetDesc(const QuerySetDesc& d, const DeviceFeatures& f) {
    const std::string what = std::string("query set '") + (d.debugName ? d.debugName : "") + "'";
    if (d.count == 0 || d.count > 4096)
        fail(what, "count " + std::to_string(d.count) + " is out of range (1..4096)");
    const bool supported = d.type == QueryType::Timestamp            ? f.timestamps
                           : d.type == QueryType::PipelineStatistics ? f.pipelineStatistics
                                                                     : f.occlusionQueries;
    if (!supported)
        fail(what, std::string(queryTypeName(d.type)) +
                       " queries are not supported on this device (DeviceFeatures::" +
                       (d.type == QueryType::Timestamp            ? "timestamps"
                        : d.type == QueryType::PipelineStatistics ? "pipelineStatistics"
                                                                  : "occlusionQueries") +
                       ")");
}

uint32_t queryValues(QueryType t) { return t == QueryType::PipelineStatistics ? 4 : 1; }

void queryDestination(const BufferDesc& d, const std::string& name, uint64_t offset,
                      uint64_t bytes) {
    const std::string what = "resolveQueries into buffer '" + name + "'";
    if (!any(d.usage, BufferUsage::CopyDst)) fail(what, "the buffer has no CopyDst usage");
    if (offset % 8) fail(what, "offset " + std::to_string(offset) + " is not a multiple of 8");
    if (offset > d.size || bytes > d.size - offset)
        fail(what, std::to_string(bytes) + " bytes at offset " + std::to_string(offset) +
                       " exceed its " + std::to_string(d.size) + " bytes");
}

void queryRead(const QuerySetDesc& d, const std::string& name, uint32_t first, uint32_t count,
               size_t outSize) {
    const std::string what = "queryResults of set '" + name + "'";
    if (count == 0 || uint64_t(first) + count > d.count)
        fail(what, "queries " + std::to_string(first) + ".." +
                       std::to_string(uint64_t(first) + count) + " are out of range (the set has " +
                       std::to_string(d.count) + ")");
    if (outSize < uint64_t(count) * queryValues(d.type))
        fail(what, "room for " + std::to_string(outSize) + " values; " +
                       std::to_string(uint64_t(count) * queryValues(d.type)) + " needed");
}

void QueryRecording::written(const QuerySetDesc& d, const std::string& name, uint32_t set,
                             uint32_t index, const char* what) {
    queryIndex(d, name, index, what);
    for (const Use& u : used_)
        if (u.set == set && u.index == index)
            fail(what,
                 queryName(name, index) +
                     " is already written in this recording (each query once per submission)");
    for (const Use& r : resolvedEarlier_)
        if (r.set == set && r.index == index)
            fail(what, queryName(name, index) +
                           " was resolved earlier in this recording, from an earlier write: "
                           "the submission resets it before it runs, so the resolve would wait "
                           "for this write");
}

void QueryRecording::begin(const QuerySetDesc& d, const std::string& name, uint32_t set,
                           uint32_t index, bool inPass) {
    if (d.type == QueryType::Timestamp)
        fail("beginQuery", "set '" + name + "' holds timestamps: use writeTimestamp");
    if (d.type != QueryType::PipelineStatistics && !inPass)
        fail("beginQuery",
             std::string(queryTypeName(d.type)) + " queries begin and end inside a render pass");
    written(d, name, set, index, "beginQuery");
    auto& active = active_[size_t(d.type)];
    if (active)
        fail("beginQuery", std::string("a ") + queryTypeName(d.type) +
                               " query is already active (" + std::to_string(active->index) +
                               "): end it first");
    active = Active{set, index, inPass};
    used_.push_back({set, index, false});
}

void QueryRecording::end(const QuerySetDesc& d, const std::string& name, uint32_t set,
                         uint32_t index, bool inPass) {
    queryIndex(d, name, index, "endQuery");
    auto& active = d.type == QueryType::Timestamp ? active_[0] : active_[size_t(d.type)];
    if (d.type == QueryType::Timestamp || !active || active->set != set || active->index != index)
        fail("endQuery", queryName(name, index) + " is not active");
    if (active->inPass != inPass)
        fail("endQuery",
             queryName(name, index) + (active->inPass
                                           ? " began inside the render pass and must end in it"
                                           : " began outside a render pass and must end outside"));
    active.reset();
    for (Use& u : used_)
        if (u.set == set && u.index == index) u.ended = true;
}

void QueryRecording::timestamp(const QuerySetDesc& d, const std::string& name, uint32_t set,
                               uint32_t index, bool inPass) {
    if (d.type != QueryType::Timestamp)
        fail("writeTimestamp", "set '" + name + "' is not a Timestamp set");
    if (inPass)
        fail("writeTimestamp", "inside a render pass (timestamps are written between passes)");
    written(d, name, set, index, "writeTimestamp");
    used_.push_back({set, index, true});
}

void QueryRecording::resolve(const QuerySetDesc& d, const std::string& name, uint32_t set,
                             uint32_t first, uint32_t count) {
    if (count == 0 || uint64_t(first) + count > d.count)
        fail("resolveQueries", "queries " + std::to_string(first) + ".." +
                                   std::to_string(uint64_t(first) + count) + " of set '" + name +
                                   "' are out of range (the set has " + std::to_string(d.count) +
                                   ")");
    std::vector<Use> earlier;  // kept only when the whole call is valid
    for (uint32_t i = first; i < first + count; ++i) {
        auto it = std::find_if(used_.begin(), used_.end(),
                               [&](const Use& u) { return u.set == set && u.index == i; });
        if (it == used_.end())
            earlier.push_back({set, i, true});  // checked against the submission
        else if (!it->ended)
            fail("resolveQueries", queryName(name, i) + " is still active (end it first)");
    }
    resolvedEarlier_.insert(resolvedEarlier_.end(), earlier.begin(), earlier.end());
}

void QueryRecording::endPass() const {
    for (const auto& a : active_)
        if (a && a->inPass)
            fail("endRenderPass",
                 "query " + std::to_string(a->index) + " begun in the pass is still active");
}

void QueryRecording::finish() const {
    for (const auto& a : active_)
        if (a)
            fail("submit", "query " + std::to_string(a->index) +
                               " is still active: end it before submitting");
    for (const auto& [timer, ended] : timers_)
        if (!ended) fail("submit", "a timer begun in this recording was not ended (endTimer)");
}

// A timer holds one span per submission: begun twice it would measure from the second begin on
// one backend and be a validation error on another; ended unbegun, GL read a negative time.
void QueryRecording::beginTimer(uint32_t timer) {
    for (const auto& t : timers_)
        if (t.first == timer)
            fail("beginTimer",
                 "the timer was already begun in this recording (one span per submission)");
    timers_.push_back({timer, false});
}

void QueryRecording::endTimer(uint32_t timer) {
    for (auto& t : timers_)
        if (t.first == timer) {
            if (t.second) fail("endTimer", "the timer was already ended in this recording");
            t.second = true;
            return;
        }
    fail("endTimer", "the timer was not begun in this recording (beginTimer first)");
}

void querySubmission(std::span<const QueryRecording* const> lists,
                     const std::function<bool(uint32_t set, uint32_t index)>& writtenBefore) {
    auto writes = [](const QueryRecording* list, const QueryRecording::Use& q) {
        return std::any_of(
            list->used().begin(), list->used().end(),
            [&](const QueryRecording::Use& u) { return u.set == q.set && u.index == q.index; });
    };
    for (size_t i = 0; i < lists.size(); ++i) {
        for (const QueryRecording::Use& u : lists[i]->used())
            for (size_t j = 0; j < i; ++j)
                if (writes(lists[j], u))
                    fail("submit", "query " + std::to_string(u.index) +
                                       " of one set is written by two lists of this "
                                       "submission (each query once per submission)");
        for (const QueryRecording::Use& r : lists[i]->resolvedEarlier()) {
            bool earlier = false, later = false;
            for (size_t j = 0; j < lists.size(); ++j)
                if (j != i && writes(lists[j], r)) (j < i ? earlier : later) = true;
            if (later)
                fail("submit", "list " + std::to_string(i) + " resolves query " +
                                   std::to_string(r.index) +
                                   " before a later list of this submission writes it (the "
                                   "submission resets it first): submit the writer earlier");
            if (!earlier && !writtenBefore(r.set, r.index))
                fail("submit", "list " + std::to_string(i) + " resolves query " +
                                   std::to_string(r.index) +
                                   " that no earlier list or submission has written");
        }
    }
}

}  // namespace fe::gdi::validate
