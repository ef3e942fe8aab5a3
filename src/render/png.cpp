// PNG output through Debian's header-only stb_image_write (libstb-dev); the implementation is
// compiled here, once.
#include <string>

#include "contour4d/core/errors.h"
#include "contour4d/io/output_dir.h"
#include "contour4d/render/renderer.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>

namespace c4d {

void write_png(const std::filesystem::path& path, const Image& image) {
  std::string bytes;
  auto sink = [](void* ctx, void* data, int size) {
    static_cast<std::string*>(ctx)->append(static_cast<const char*>(data), static_cast<std::size_t>(size));
  };
  if (!stbi_write_png_to_func(sink, &bytes, image.width, image.height, 4, image.rgba.data(), image.width * 4))
    throw IoError(ErrorCode::OutputNotWritable, {path.string()}, "PNG encoding failed", "check the image size");
  write_file_atomic(path, bytes);
}

}  // namespace c4d
