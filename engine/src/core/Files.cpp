// File reads and atomic writes.
#include "engine/core/Files.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <random>
#include <system_error>
#include <unistd.h>

namespace core {
namespace {

Error fileError(const char* function, const std::filesystem::path& path, const std::string& what) {
    return Error{std::string(function) + ": " + path.string() + ": " + what};
}

} // namespace

Result<std::vector<std::uint8_t>> readFile(const std::filesystem::path& path,
                                           std::uint64_t maxBytes) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        return fileError("core::readFile()", path, "no such file");
    const std::uint64_t size = std::filesystem::file_size(path, ec);
    if (ec)
        return fileError("core::readFile()", path, ec.message());
    if (size > maxBytes)
        return fileError("core::readFile()", path,
                         std::to_string(size) + " bytes, over the limit of " +
                             std::to_string(maxBytes));
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (!file)
        return fileError("core::readFile()", path, std::strerror(errno));
    std::vector<std::uint8_t> bytes(size);
    const std::size_t got = size ? std::fread(bytes.data(), 1, size, file) : 0;
    std::fclose(file);
    if (got != size)
        return fileError("core::readFile()", path, "short read");
    return bytes;
}

Status writeFileAtomic(const std::filesystem::path& path, std::span<const std::uint8_t> bytes) {
    std::random_device random;
    std::filesystem::path temporary = path;
    temporary += ".tmp" + std::to_string(random() % 1000000u);
    std::FILE* file = std::fopen(temporary.c_str(), "wb");
    if (!file)
        return fileError("core::writeFileAtomic()", path, std::strerror(errno));
    bool good = bytes.empty() || std::fwrite(bytes.data(), 1, bytes.size(), file) == bytes.size();
    good = std::fflush(file) == 0 && good;
    good = ::fsync(fileno(file)) == 0 && good;
    good = std::fclose(file) == 0 && good;
    if (!good) {
        const std::string reason = std::strerror(errno);
        std::remove(temporary.c_str());
        return fileError("core::writeFileAtomic()", path, "write failed: " + reason);
    }
    if (std::rename(temporary.c_str(), path.c_str()) != 0) {
        const std::string reason = std::strerror(errno);
        std::remove(temporary.c_str());
        return fileError("core::writeFileAtomic()", path, "rename failed: " + reason);
    }
    return {};
}

Status writeFileAtomic(const std::filesystem::path& path, const std::string& text) {
    return writeFileAtomic(
        path, std::span(reinterpret_cast<const std::uint8_t*>(text.data()), text.size()));
}

} // namespace core
