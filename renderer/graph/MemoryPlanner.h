// Layer 6: places the transient textures of a compiled graph in memory.
//   Memory:      one heap; each texture gets the lowest aligned offset whose bytes no texture
//                with an overlapping lifetime occupies (greedy, largest first).
//   ObjectReuse: a texture takes over an earlier texture's object when format, size and mip
//                count match and the earlier one's last use precedes its first use; the object
//                is created with the union of their usages.
//   None:        every texture has memory of its own.
// Written by hand: the interval placement is a few dozen lines and no packaged library does it.
#pragma once
#include <vector>

#include "graph/GraphTypes.h"

namespace fe::graph {

// Fills offset and physical of every used transient texture (size/alignment must be set)
// and returns the totals. Imported and unused textures are left alone.
MemoryReport planMemory(std::vector<TextureInfo>& textures, AliasingMode mode);

}  // namespace fe::graph
