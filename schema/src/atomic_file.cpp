#include "sandpaper/schema/atomic_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace sandpaper::schema {

void write_file_atomically(const std::filesystem::path& path, std::string_view bytes) {
  write_file_atomically(path, std::vector<std::string_view>{bytes});
}

void write_file_atomically(const std::filesystem::path& path, const std::vector<std::string_view>& parts) {
  std::filesystem::path dir = path.parent_path();
  if (dir.empty()) dir = ".";
  std::string tmpl = (dir / ("." + path.filename().string() + ".tmp-XXXXXX")).string();
  int fd = mkstemp(tmpl.data());
  if (fd < 0)
    throw std::runtime_error("cannot write '" + path.string() + "': " + std::strerror(errno));
  for (const std::string_view bytes : parts) {
    const char* p = bytes.data();
    std::size_t left = bytes.size();
    while (left > 0) {
      ssize_t n = ::write(fd, p, left);
      if (n < 0) {
        if (errno == EINTR) continue;
        int e = errno;
        ::close(fd);
        ::unlink(tmpl.c_str());
        throw std::runtime_error("cannot write '" + path.string() + "': " + std::strerror(e));
      }
      p += n;
      left -= static_cast<std::size_t>(n);
    }
  }
  // mkstemp makes 0600 files; outputs are ordinary files.
  ::fchmod(fd, 0644);
  if (::close(fd) != 0 || std::rename(tmpl.c_str(), path.c_str()) != 0) {
    int e = errno;
    ::unlink(tmpl.c_str());
    throw std::runtime_error("cannot write '" + path.string() + "': " + std::strerror(e));
  }
}

}  // namespace sandpaper::schema
