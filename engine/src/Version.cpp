// The shared engine library's own translation unit: its version (the modules are linked whole).
#include "engine/core/Version.h"

namespace core {

const char* engineVersion() {
    return GLASS_VERSION;
}

} // namespace core
