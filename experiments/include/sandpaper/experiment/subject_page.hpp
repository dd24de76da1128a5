#pragma once
// The subject's full-screen page (docs/EXPERIMENTS.md, "The subject's page"): an observer whose
// answers come from a browser. The experiment process serves the page itself (http/local_server.hpp,
// the server and Host/Origin guard the studio uses too); the page long-polls GET /api/screen for what
// to show and POSTs each answer to /api/answer, which checks it against the screen it answers.
#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "sandpaper/experiment/observer.hpp"
#include "sandpaper/http/local_server.hpp"

namespace sandpaper::experiment {

// The page's files (experiments/web/), compiled in by cmake/embed_files.cmake.
using PageAsset = http::Asset;
const std::vector<PageAsset>& page_assets();

class PageObserver;

// Serves the page on `listen` ("127.0.0.1:4781"; port 0: any free port) until destroyed. `stop`, when
// set (by a signal handler), makes a pending question return "stopped". Throws std::invalid_argument
// for a bad address and std::runtime_error when it cannot listen.
std::unique_ptr<Observer> make_page_observer(const std::string& listen, const std::atomic<bool>* stop, std::string& url);

}  // namespace sandpaper::experiment
