// The engine's version, as the library a program runs against reports it.
#pragma once

namespace core {

/** "MAJOR.MINOR.PATCH" of the libglass-engine this program runs with (the project version;
 *  README "Versioning"). */
const char* engineVersion();

} // namespace core
