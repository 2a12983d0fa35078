// JPEG through libjpeg-turbo: errors return through longjmp to the function that set the jump,
// which holds nothing with a destructor between setjmp and the calls that may jump.
#include "JpegDecoder.h"

// clang-format off
#include <cstdio> // jpeglib.h needs FILE declared first
#include <jpeglib.h>
// clang-format on

#include <csetjmp>
#include <cstring>

namespace asset::detail {
namespace {

constexpr int kMaxScans = 256;

/** libjpeg's error manager first, so that the library's pointer to it is a pointer to this. */
struct Failure {
    jpeg_error_mgr manager;
    std::jmp_buf jump;
    char message[JMSG_LENGTH_MAX];
};

[[noreturn]] void onError(j_common_ptr info) {
    Failure* failure = reinterpret_cast<Failure*>(info->err);
    info->err->format_message(info, failure->message);
    std::longjmp(failure->jump, 1);
}

void onMessage(j_common_ptr) {} // warnings are not printed

void onProgress(j_common_ptr info) {
    if (!info->is_decompressor)
        return;
    const auto* decompress = reinterpret_cast<j_decompress_ptr>(info);
    if (decompress->input_scan_number > kMaxScans) {
        Failure* failure = reinterpret_cast<Failure*>(info->err);
        std::snprintf(failure->message, sizeof failure->message,
                      "more than %d scans (progressive JPEG)", kMaxScans);
        std::longjmp(failure->jump, 1);
    }
}

/** The header, and the pixels when `channels` is 3 or 4, into `out`. */
void run(std::span<const std::uint8_t> bytes, int channels, Jpeg& out) {
    jpeg_decompress_struct info;
    std::memset(&info, 0, sizeof info);
    Failure failure;
    std::memset(&failure, 0, sizeof failure);
    jpeg_progress_mgr progress;
    std::memset(&progress, 0, sizeof progress);
    info.err = jpeg_std_error(&failure.manager);
    failure.manager.error_exit = onError;
    failure.manager.output_message = onMessage;
    progress.progress_monitor = onProgress;
    if (setjmp(failure.jump)) {
        jpeg_destroy_decompress(&info);
        out.error = failure.message[0] ? failure.message : "corrupt JPEG data";
        return;
    }
    jpeg_create_decompress(&info);
    info.progress = &progress;
    jpeg_mem_src(&info, bytes.data(), static_cast<unsigned long>(bytes.size()));
    jpeg_read_header(&info, TRUE);
    out.width = int(info.image_width);
    out.height = int(info.image_height);
    if (channels == 3 || channels == 4) {
        info.out_color_space = channels == 4 ? JCS_EXT_RGBA : JCS_RGB;
        jpeg_start_decompress(&info);
        const std::size_t row = std::size_t(info.output_width) * std::size_t(channels);
        out.pixels.resize(row * std::size_t(info.output_height));
        while (info.output_scanline < info.output_height) {
            JSAMPROW line = out.pixels.data() + std::size_t(info.output_scanline) * row;
            jpeg_read_scanlines(&info, &line, 1);
        }
        jpeg_finish_decompress(&info);
    }
    jpeg_destroy_decompress(&info);
}

} // namespace

Jpeg jpegHeader(std::span<const std::uint8_t> bytes) {
    Jpeg jpeg;
    run(bytes, 0, jpeg);
    return jpeg;
}

Jpeg decodeJpeg(std::span<const std::uint8_t> bytes, int channels) {
    Jpeg jpeg;
    run(bytes, channels, jpeg);
    if (!jpeg.error.empty())
        jpeg.pixels.clear();
    return jpeg;
}

} // namespace asset::detail
