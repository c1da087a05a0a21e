#include "fmi/zip_writer.h"

#include <stdexcept>

#include <zip.h>

namespace mechflow::fmi {

void WriteZip(const std::string& path, const std::vector<ZipEntry>& entries) {
  int error = 0;
  zip_t* archive = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  if (!archive) {
    zip_error_t e;
    zip_error_init_with_code(&e, error);
    const std::string why = zip_error_strerror(&e);
    zip_error_fini(&e);
    throw std::runtime_error("cannot write '" + path + "': " + why);
  }
  const auto fail = [&](const std::string& what) {
    const std::string why = zip_strerror(archive);
    zip_discard(archive);
    throw std::runtime_error("cannot write '" + path + "': " + what + ": " + why);
  };
  for (const ZipEntry& e : entries) {
    // libzip reads the sources when the archive is closed: the strings live until then
    zip_source_t* source = e.file.empty() ? zip_source_buffer(archive, e.content.data(), e.content.size(), 0)
                                          : zip_source_file(archive, e.file.c_str(), 0, -1);
    if (!source) fail(e.file.empty() ? e.name : e.file);
    const zip_int64_t index = zip_file_add(archive, e.name.c_str(), source, ZIP_FL_ENC_UTF_8 | ZIP_FL_OVERWRITE);
    if (index < 0) {
      zip_source_free(source);
      fail(e.name);
    }
    // level 1: 2.1 MB instead of 1.9 at the default level, in 0.16 s instead of 1 s
    zip_set_file_compression(archive, static_cast<zip_uint64_t>(index), ZIP_CM_DEFLATE, 1);
  }
  if (zip_close(archive) != 0) fail("closing the archive");
}

}  // namespace mechflow::fmi
