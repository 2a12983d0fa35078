// Minimal leveled logging to stderr; the level is process-wide.
#pragma once

#include <string_view>

namespace core {

enum class LogLevel { Debug, Info, Warning, Error, Off };

/** Messages below this level are dropped. Default: Info, or GLASS_LOG=debug|info|warning|error|off.
 */
void setLogLevel(LogLevel level);
LogLevel logLevel();

/** Writes "[level] message" to stderr when `level` passes the threshold. Thread-safe. */
void log(LogLevel level, std::string_view message);

inline void logDebug(std::string_view m) {
    log(LogLevel::Debug, m);
}
inline void logInfo(std::string_view m) {
    log(LogLevel::Info, m);
}
inline void logWarning(std::string_view m) {
    log(LogLevel::Warning, m);
}
inline void logError(std::string_view m) {
    log(LogLevel::Error, m);
}

} // namespace core
