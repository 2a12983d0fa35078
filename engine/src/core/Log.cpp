// Leveled logging to stderr.
#include "engine/core/Log.h"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string>

namespace core {
namespace {

LogLevel levelFromEnvironment() {
    const char* value = std::getenv("GLASS_LOG");
    if (!value)
        return LogLevel::Info;
    const std::string s(value);
    if (s == "debug")
        return LogLevel::Debug;
    if (s == "warning")
        return LogLevel::Warning;
    if (s == "error")
        return LogLevel::Error;
    if (s == "off")
        return LogLevel::Off;
    return LogLevel::Info;
}

std::atomic<LogLevel>& threshold() {
    static std::atomic<LogLevel> level{levelFromEnvironment()};
    return level;
}

const char* levelName(LogLevel level) {
    switch (level) {
    case LogLevel::Debug:
        return "debug";
    case LogLevel::Info:
        return "info";
    case LogLevel::Warning:
        return "warning";
    case LogLevel::Error:
        return "error";
    case LogLevel::Off:
        break;
    }
    return "?";
}

} // namespace

void setLogLevel(LogLevel level) {
    threshold().store(level);
}
LogLevel logLevel() {
    return threshold().load();
}

void log(LogLevel level, std::string_view message) {
    if (level < threshold().load() || level == LogLevel::Off)
        return;
    static std::mutex mutex;
    const std::lock_guard lock(mutex);
    std::fprintf(stderr, "[%s] %.*s\n", levelName(level), int(message.size()), message.data());
}

} // namespace core
