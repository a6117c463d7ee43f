// fe bisect: the first render pass, then the first draw in it, where two devices' replays of one
// capture disagree. Linear in passes and draws (not a binary search): a later draw may cover
// what an earlier one got wrong, so only the first differing state is a sure answer.
#include "fe/gdi/Capture.h"

namespace fe::gdi {

namespace {

std::optional<uint64_t> skipFor(const BisectOptions& o, int device) {
    if (o.perturb && o.perturb->first == device) return o.perturb->second;
    return std::nullopt;
}

// The targets of `a` and `b` (same capture: same targets in the same order) that differ.
std::vector<TargetDiff> differing(const std::vector<ReplayImage>& a,
                                  const std::vector<ReplayImage>& b, const BisectOptions& o) {
    std::vector<TargetDiff> out;
    for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
        const Image& x = a[i].image;
        const Image& y = b[i].image;
        TargetDiff d{.target = a[i].name, .a = x, .b = y};
        if (x.width != y.width || x.height != y.height || x.format != y.format) {
            d.diff.pixels = d.diff.pixelsOverTolerance = std::max(x.width * x.height, 1u);
            out.push_back(std::move(d));
            continue;
        }
        d.diff = compareImages(x, y, o.absTolerance, 0.0, &d.heat);
        if (d.diff.fractionOver() > o.maxFractionOver) out.push_back(std::move(d));
    }
    if (a.size() != b.size())
        out.push_back({.target = "(the two replays read different numbers of targets)"});
    return out;
}

}  // namespace

BisectResult bisectCapture(const std::string& path, Device& a, Device& b, const BisectOptions& o) {
    BisectResult result;
    auto replay = [&](Device& d, int which, ReplayOptions options) {
        options.skipDraw = skipFor(o, which);
        ++result.replays;
        return replayCapture(path, d, options);
    };
    const ReplayResult ra = replay(a, 0, {.snapshotPasses = true});
    const ReplayResult rb = replay(b, 1, {.snapshotPasses = true});
    const size_t passes = std::min(ra.passSnapshots.size(), rb.passSnapshots.size());
    for (size_t p = 0; p < passes && !result.pass; ++p) {
        ++result.passesCompared;
        auto diffs = differing(ra.passSnapshots[p].targets, rb.passSnapshots[p].targets, o);
        if (diffs.empty()) continue;
        result.diverged = true;
        result.pass = ra.passSnapshots[p];
        result.diffs = std::move(diffs);
    }
    if (!result.pass) {
        // No render pass differs: what the program read back may (compute, copies).
        result.diffs = differing(ra.images, rb.images, o);
        result.diverged = !result.diffs.empty();
        return result;
    }
    const PassSnapshot& pass = *result.pass;
    for (uint64_t draw = pass.firstDraw; draw < pass.firstDraw + pass.draws; ++draw) {
        ++result.drawsCompared;
        const ReplayResult da = replay(a, 0, {.stopAfterDraw = draw});
        const ReplayResult db = replay(b, 1, {.stopAfterDraw = draw});
        if (!da.stopTargets || !db.stopTargets)
            continue;  // the draw was left out (perturbed) on one side
        auto diffs = differing(da.stopTargets->targets, db.stopTargets->targets, o);
        if (diffs.empty()) continue;
        result.draw = da.stoppedAt ? da.stoppedAt : db.stoppedAt;
        result.diffs = std::move(diffs);
        break;
    }
    return result;
}

}  // namespace fe::gdi
