// fe capture and fe replay: capture files (gdi/include/fe/gdi/Capture.h, docs/CAPTURE.md).
#pragma once
#include "Cli.h"

namespace fe::cli {

// fe capture [--out FILE] [--frames N] [--no-compress] -- PROGRAM [ARGS...]: runs PROGRAM with
// FE_CAPTURE set, so its first device is captured without a change to it; prints what the file
// holds. Exit code: PROGRAM's.
int cmdCapture(int argc, char** argv);
// fe replay FILE [--backend NAME] [--out DIR] [--validation] [--present] [--pass NAME | --draw N]
int cmdReplay(const Args& a);
// fe bisect FILE [--backends A,B] [--tolerance ABS[,FRACTION]] [--out DIR] [--perturb BACKEND:DRAW]
// Exit code 0: the backends agree; 1: they differ (the report says where).
int cmdBisect(const Args& a, const std::vector<std::string>& arguments);

}  // namespace fe::cli
