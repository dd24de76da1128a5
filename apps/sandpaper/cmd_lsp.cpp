#include <iostream>

#include "cli.hpp"
#include "sandpaper/lsp/server.hpp"

namespace sandpaper::cli {

int cmd_lsp(const CommonOptions& o) {
  const compiler::Compiler c = make_compiler(o);
  // stdout carries only protocol messages: everything else goes to stderr.
  std::ios::sync_with_stdio(false);
  return lsp::serve(std::cin, std::cout, std::cerr, c);
}

}  // namespace sandpaper::cli
