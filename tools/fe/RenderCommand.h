// fe render: a scene rendered with a lighting technique to .png / .pfm, its figures printed as a
// short summary (--verbose: passes, memory, light lists), as JSON (--json) or not at all (--quiet).
#pragma once
#include <string>
#include <vector>

#include "Cli.h"

namespace fe::cli {

int cmdRender(const Args& a);

// The technique-specific options given (--msaa, --illum-scale, ...) that technique s.technique
// does not use: reset in `s`, one warning each ("--msaa has no effect on technique redeferred (it
// applies to ...): ignored").
std::vector<std::string> dropUnusedTechniqueOptions(const Args& a, render::RenderSettings& s);

}  // namespace fe::cli
