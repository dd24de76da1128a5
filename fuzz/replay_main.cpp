// Replays fuzz inputs without libFuzzer: runs LLVMFuzzerTestOneInput once on each file named on the
// command line and on each regular file of each folder named (sorted, not recursive; README.md
// and .gitkeep are skipped), so that the normal build's tests (`fuzz.replay.<target>`) keep every
// corpus input and every saved crash passing, sanitizers or not. Each file's name is printed
// before it runs, so a crash names the input that caused it.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

namespace fs = std::filesystem;

bool is_input(const fs::path& p) {
  const auto name = p.filename().string();
  return name != "README.md" && name != ".gitkeep";
}

int replay(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    std::fprintf(stderr, "replay: cannot read %s\n", file.c_str());
    return 1;
  }
  const std::vector<char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  std::fprintf(stderr, "replay: %s (%zu bytes)\n", file.c_str(), bytes.size());
  // A copy on the heap of exactly its size, as libFuzzer passes it: ASan sees reads past the end.
  // An empty input still gets a valid pointer, as from libFuzzer.
  std::vector<std::uint8_t> exact(bytes.begin(), bytes.end());
  static std::uint8_t none = 0;
  LLVMFuzzerTestOneInput(exact.empty() ? &none : exact.data(), exact.size());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s FILE|FOLDER...\n", argv[0]);
    return 2;
  }
  std::size_t replayed = 0;
  for (int i = 1; i < argc; ++i) {
    const fs::path arg = argv[i];
    std::vector<fs::path> files;
    if (fs::is_directory(arg)) {
      for (const auto& e : fs::directory_iterator(arg))
        if (e.is_regular_file() && is_input(e.path())) files.push_back(e.path());
      std::sort(files.begin(), files.end());
    } else if (fs::is_regular_file(arg)) {
      files.push_back(arg);
    } else {
      std::fprintf(stderr, "replay: no such file or folder: %s\n", arg.c_str());
      return 2;
    }
    for (const auto& f : files) {
      if (replay(f) != 0) return 1;
      ++replayed;
    }
  }
  std::printf("replayed %zu inputs\n", replayed);
  return 0;
}
