#include "fe/gdi/ShaderRegistry.h"

#include <map>
#include <string>

namespace fe::shaders {

namespace {
std::map<std::string, gdi::ShaderBinary, std::less<>>& registry() {
    static std::map<std::string, gdi::ShaderBinary, std::less<>> r;  // constructed on first use
    return r;
}
}  // namespace

void registerBinary(const gdi::ShaderBinary& binary) { registry()[binary.name] = binary; }

const gdi::ShaderBinary& find(std::string_view name) {
    auto it = registry().find(name);
    if (it == registry().end())
        throw gdi::Error("shader '" + std::string(name) + "' is not compiled into this program");
    return it->second;
}

std::vector<std::string_view> names() {
    std::vector<std::string_view> out;
    for (auto& [k, v] : registry()) out.push_back(k);
    return out;
}

}  // namespace fe::shaders
