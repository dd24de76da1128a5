// The picture table loaded on first use from libsandpaper_image_io.so (image_io.hpp says why). Built
// in variants like data_dirs.cpp (compiler/CMakeLists.txt): for the build tree, the module beside the
// build's other outputs; for an install, the module found from where the running program lies (a
// moved install works), then the configured prefix. $SANDPAPER_IMAGE_IO names a module to use instead.
#include <dlfcn.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

#include "sandpaper/compiler/diagnostic.hpp"
#include "sandpaper/compiler/image_io.hpp"

namespace sandpaper::compiler::image_io {
namespace {

std::vector<std::string> candidates() {
  std::vector<std::string> c;
  if (const char* env = std::getenv("SANDPAPER_IMAGE_IO"); env && *env) {
    c.emplace_back(env);
    return c;
  }
#ifdef SANDPAPER_IMAGE_IO_BIN_TO_MODULE
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) c.push_back((exe.parent_path() / SANDPAPER_IMAGE_IO_BIN_TO_MODULE).lexically_normal().string());
#endif
  c.emplace_back(SANDPAPER_IMAGE_IO_PATH);
  return c;
}

struct Loaded {
  const Api* table = nullptr;
  std::string path;
};

Loaded load() {
  using Entry = const Api* (*)();
  std::string tried;
  for (const auto& path : candidates()) {
    tried += "\n  " + path + ": ";
    if (::access(path.c_str(), R_OK) != 0) {
      tried += std::strerror(errno);
      continue;
    }
    // RTLD_LOCAL: OpenImageIO's symbols stay out of the program's namespace.
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* e = ::dlerror();
      tried += e ? e : "cannot be loaded";
      continue;
    }
    auto entry = reinterpret_cast<Entry>(::dlsym(handle, "sandpaper_image_io_table"));
    const Api* table = entry ? entry() : nullptr;
    if (!table || table->abi != kAbi || !table->build || std::strcmp(table->build, SANDPAPER_IMAGE_IO_BUILD) != 0) {
      tried += std::string("built for another Sandpaper (") + (table && table->build ? table->build : "no version") +
               ", this is " + SANDPAPER_IMAGE_IO_BUILD + ")";
      ::dlclose(handle);
      continue;
    }
    return {table, path};  // kept loaded for the life of the program
  }
  throw InternalError("Sandpaper's picture module libsandpaper_image_io.so cannot be loaded; looked in:" + tried +
                      "\nreinstall Sandpaper, or set SANDPAPER_IMAGE_IO to the module's path");
}

std::mutex loading;
Loaded loaded;

}  // namespace

const Api& api() {
  // Not a function-local static: a failed load throws, and the next call tries again and says why.
  const std::lock_guard lock(loading);
  if (!loaded.table) loaded = load();
  return *loaded.table;
}

std::string provider() {
  const std::lock_guard lock(loading);
  return loaded.path;
}

}  // namespace sandpaper::compiler::image_io
