// Layer 5 (Communication: Asset Loader): the one exception type of the asset layer.
#pragma once
#include <stdexcept>
#include <string>

namespace fe::assets {

// Every load failure (missing file, malformed glTF, out-of-range data, unsupported required
// feature, unknown builtin name) is reported as an AssetError whose message names the file and
// the offending element, e.g. "Box.gltf: accessor 3 (POSITION of mesh 'Box' primitive 0): ...".
class AssetError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace fe::assets
