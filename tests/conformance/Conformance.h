// The conformance suite: each case is recorded once against the abstract device and run on
// every backend; its images are checked against analytic expectations and, by `fe
// conformance --backend all`, against the other backends.
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "fe/gdi/Device.h"

namespace fe::conformance {

struct CaseImage {
    std::string name;
    gdi::Image image;
    gdi::Image expected;  // empty: no analytic expectation
    double absTolerance = 5.0 / 255.0;
    double maxFractionOver = 0.001;  // 8-bit rule: at most 0.1% of pixels over 5/255
    std::string toleranceReason = "8-bit target: 0.1% of pixels may differ by more than 5/255";
    // Set by runCase: `image` against `expected` (reports carry the metrics, not just pass/fail).
    std::optional<gdi::ImageDiff> diff;
    bool passed() const { return !diff || diff->fractionOver() <= maxFractionOver; }
};

struct CaseResult {
    std::string caseName;
    std::vector<CaseImage> images;
    bool passed = true;
    std::string message;
};

struct Case {
    std::string name;
    std::function<std::vector<CaseImage>(gdi::Device&)> run;
};

// A check inside a case for what an image cannot show (a duration, a byte count, a feature):
// failing it fails the case, and the message names the file and line.
[[noreturn]] void checkFailed(const char* file, int line, const char* condition, const char* what);
#define FE_CONFORMANCE_CHECK(condition, what)                                                   \
    do {                                                                                        \
        if (!(condition)) ::fe::conformance::checkFailed(__FILE__, __LINE__, #condition, what); \
    } while (0)

const std::vector<Case>& cases();
// A capture file (gdi/Capture.h) as a case: its read-back and presented images, replayed.
Case captureCase(const std::string& path);
// Runs one case: exceptions and validation errors fail it; analytic expectations are compared.
CaseResult runCase(gdi::Device& device, const Case& c);

}  // namespace fe::conformance
