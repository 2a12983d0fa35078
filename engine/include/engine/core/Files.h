// Whole-file reads and atomic writes (temporary file + rename: never a half-written output).
#pragma once

#include "engine/core/Result.h"

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace core {

/** Reads a whole file. Fails naming the path when it is missing, unreadable or larger than
 *  `maxBytes`. */
Result<std::vector<std::uint8_t>> readFile(const std::filesystem::path& path,
                                           std::uint64_t maxBytes = std::uint64_t(4) << 30);

/** Writes `bytes` to `path` atomically: a temporary file beside it is written, flushed and
 *  renamed over `path`. On failure `path` is untouched and the temporary file removed. */
Status writeFileAtomic(const std::filesystem::path& path, std::span<const std::uint8_t> bytes);
Status writeFileAtomic(const std::filesystem::path& path, const std::string& text);

} // namespace core
