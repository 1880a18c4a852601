// fabmesh studio DESIGN.yaml [--port N] [--host ADDR] [--no-open] [-o OUTDIR]: a local web page
// that builds the design as its parameters move (docs/studio.md).

#include <fcntl.h>
#include <fmt/format.h>
#include <pthread.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <memory>
#include <thread>

#include "pipeline/cli/commands.h"
#include "pipeline/studio/studio_server.h"
#include "pipeline/studio/studio_session.h"

namespace fabmesh::cli {
namespace {

namespace fs = std::filesystem;

struct StudioArgs {
  std::string design;
  std::string host = "127.0.0.1";
  int port = 0;
  bool no_open = false;
  std::string out = "out";
};

// Where the page's files are, from the folder of the running program
// (FABMESH_STUDIO_FROM_PROGRAM: "../share/fabmesh/studio" for an installed
// bin/fabmesh; the build puts a copy at the same place).
fs::path page_folder() {
  std::error_code ec;
  const fs::path program = fs::read_symlink("/proc/self/exe", ec);
  if (ec || program.empty()) return {};
  return (program.parent_path() / FABMESH_STUDIO_FROM_PROGRAM).lexically_normal();
}

// Starts `xdg-open url` without waiting for it, with the signal mask `mask`
// (not the studio's, which blocks SIGINT and SIGTERM); its pid, or -1 when it could not start.
pid_t open_in_browser(const std::string& url, const sigset_t& mask) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  posix_spawnattr_setsigmask(&attributes, &mask);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK);
  std::string program = "xdg-open";
  std::string argument = url;
  char* argv[] = {program.data(), argument.data(), nullptr};
  pid_t pid = -1;
  const int error = posix_spawnp(&pid, program.c_str(), &actions, &attributes, argv, environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  return error == 0 ? pid : -1;
}

// Blocks SIGINT and SIGTERM in this thread (and the threads it starts) while
// it lives. Once one has come (wait), the studio is ending: any further one
// is ignored until it has ended, so that a second Ctrl-C or SIGTERM during
// the shutdown cannot kill it (exit 143) instead of its clean exit 0.
class BlockedSignals {
 public:
  BlockedSignals() {
    sigemptyset(&signals_);
    sigaddset(&signals_, SIGINT);
    sigaddset(&signals_, SIGTERM);
    pthread_sigmask(SIG_BLOCK, &signals_, &previous_);
  }
  BlockedSignals(const BlockedSignals&) = delete;
  BlockedSignals& operator=(const BlockedSignals&) = delete;
  ~BlockedSignals() {
    pthread_sigmask(SIG_SETMASK, &previous_, nullptr);
    if (ignoring_) {
      sigaction(SIGINT, &previous_int_, nullptr);
      sigaction(SIGTERM, &previous_term_, nullptr);
    }
  }
  /// Waits for one of them, then ignores them: a pending one is dropped, so
  /// that unblocking them later delivers nothing.
  void wait() {
    int signal = 0;
    sigwait(&signals_, &signal);
    struct sigaction ignore {};
    ignore.sa_handler = SIG_IGN;
    sigemptyset(&ignore.sa_mask);
    sigaction(SIGINT, &ignore, &previous_int_);
    sigaction(SIGTERM, &ignore, &previous_term_);
    ignoring_ = true;
  }
  /// The mask the program had before: what a child it starts gets.
  const sigset_t& previous() const { return previous_; }

 private:
  sigset_t signals_{};
  sigset_t previous_{};
  struct sigaction previous_int_ {};
  struct sigaction previous_term_ {};
  bool ignoring_ = false;  ///< set by wait(), read once the waiting thread has been joined
};

int studio(const StudioArgs& args, Streams io) {
  // SIGINT and SIGTERM are taken by one thread that stops the server: block
  // them here, before any other thread starts, so that every thread inherits it.
  BlockedSignals signals;
  StudioSessionOptions session_options;
  session_options.design_path = args.design;
  session_options.out_dir = args.out;
  StudioSession session(session_options);
  StudioServerOptions options;
  options.host = args.host;
  options.port = args.port;
  options.web_root = page_folder().string();
  StudioServer server(session, options);
  io.out << server.url() << std::endl;
  if (io.verbosity > 0) {
    io.err << fmt::format("fabmesh studio: {} (outputs to {}/); Ctrl-C ends it\n", args.design, args.out);
  }
  pid_t browser = -1;
  if (!args.no_open) {
    browser = open_in_browser(server.url(), signals.previous());
    if (browser < 0) io.err << "fabmesh studio: could not start xdg-open; open the address above yourself\n";
  }
  std::thread waiter([&server, &signals] {
    signals.wait();
    server.stop();
  });
  server.run();
  // run() ends only by stop(), which only the waiter calls: it has its signal.
  waiter.join();
  if (browser > 0) waitpid(browser, nullptr, WNOHANG);
  if (io.verbosity > 0) io.err << "fabmesh studio: stopped\n";
  return 0;
}

}  // namespace

Runner add_studio_command(CLI::App& app) {
  auto args = std::make_shared<StudioArgs>();
  CLI::App* cmd =
      app.add_subcommand("studio",
                         "Shape a design in the browser: sliders for its parameters, the curve plot, the 3D "
                         "mesh and the report, "
                         "rebuilt as you move them; save and export (a local web server, docs/studio.md)");
  cmd->add_option("design", args->design, "The design file (YAML)")->required();
  cmd->add_option("--port", args->port, "The port to listen on (default 0: a free one, printed)")
      ->check(CLI::Range(0, 65535));
  cmd->add_option("--host", args->host,
                  "The address to listen on (default 127.0.0.1: this machine only; the token still applies)");
  cmd->add_flag("--no-open", args->no_open, "Do not open the page in a browser (xdg-open)");
  cmd->add_option("-o,--output", args->out, "The folder export writes to (default: out)");
  return [args](Streams io) { return studio(*args, io); };
}

}  // namespace fabmesh::cli
