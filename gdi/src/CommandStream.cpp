#include "fe/gdi/CommandStream.h"

namespace fe::gdi::cmd {

const char* opName(Op op) {
    switch (op) {
#define FE_COMMAND(Name, Fields) \
    case Op::Name:               \
        return #Name;
#include "fe/gdi/CommandSet.inc"
#undef FE_COMMAND
        default:
            return "unknown";
    }
}

}  // namespace fe::gdi::cmd
