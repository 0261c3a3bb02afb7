#include "postprocess/render/headless_display.hpp"

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <poll.h>
#include <stdexcept>
#include <sys/wait.h>
#include <unistd.h>

#include <X11/Xlib.h>

namespace grains::postprocess {

namespace {

// Whether an X client can connect to `display` now.
bool can_open(const std::string& display) {
  Display* d = XOpenDisplay(display.c_str());
  if (!d) return false;
  XCloseDisplay(d);
  return true;
}

}  // namespace

HeadlessDisplay::HeadlessDisplay() {
  // A DISPLAY that cannot be opened (a stale one from an ssh session, say)
  // would make VTK abort the process: start a private Xvfb instead.
  if (const char* d = std::getenv("DISPLAY"); d && *d && can_open(d)) {
    display_ = d;
    return;
  }
  int fds[2];
  if (pipe(fds) != 0) throw std::runtime_error(std::string("cannot start Xvfb: pipe: ") + std::strerror(errno));
  const std::string fd = std::to_string(fds[1]);
  const pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    throw std::runtime_error(std::string("cannot start Xvfb: fork: ") + std::strerror(errno));
  }
  if (pid == 0) {
    close(fds[0]);
    const int null = open("/dev/null", O_RDWR);
    if (null >= 0) {
      dup2(null, STDIN_FILENO);
      dup2(null, STDOUT_FILENO);
      dup2(null, STDERR_FILENO);
    }
    // -noreset: an X server resets when its last client disconnects, and
    // connections made meanwhile fail (VTK then aborts); the check below
    // connects and disconnects right before VTK connects.
    execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1920x1200x24", "-nolisten", "tcp", "-noreset",
           static_cast<char*>(nullptr));
    _exit(127);
  }
  close(fds[1]);
  std::string out;
  char buf[64];
  pollfd p{fds[0], POLLIN, 0};
  // Xvfb writes the display number and a newline once it accepts connections.
  while (out.find('\n') == std::string::npos) {
    const int ready = poll(&p, 1, 15000);
    if (ready <= 0) break;
    const ssize_t k = read(fds[0], buf, sizeof buf);
    if (k <= 0) break;
    out.append(buf, static_cast<std::size_t>(k));
  }
  close(fds[0]);
  const auto nl = out.find('\n');
  if (nl == std::string::npos || nl == 0) {
    kill(pid, SIGTERM);
    int status = 0;
    waitpid(pid, &status, 0);
    const bool missing = WIFEXITED(status) && WEXITSTATUS(status) == 127;
    throw std::runtime_error(missing ? "no X display: DISPLAY is unset and Xvfb is not installed (Debian package xvfb); "
                                       "install it or run under a display"
                                     : "no X display: DISPLAY is unset and Xvfb did not start");
  }
  pid_ = pid;
  display_ = out.substr(0, nl);
  display_.insert(display_.begin(), ':');
  // Xvfb reports the display once it listens; make sure a client can
  // connect before VTK tries (VTK aborts when it cannot), retrying briefly
  // on a loaded machine.
  bool open = false;
  for (int attempt = 0; attempt < 50 && !(open = can_open(display_)); ++attempt) usleep(100000);
  if (!open) {
    kill(pid_, SIGTERM);
    int status = 0;
    waitpid(pid_, &status, 0);
    pid_ = -1;
    throw std::runtime_error("no X display: Xvfb started on " + display_ +
                             " but no client could connect to it within 5 s; set DISPLAY to a reachable X server");
  }
  if (const char* d = std::getenv("DISPLAY")) previous_ = d;
  setenv("DISPLAY", display_.c_str(), 1);
}

HeadlessDisplay::~HeadlessDisplay() {
  if (pid_ <= 0) return;
  if (previous_)
    setenv("DISPLAY", previous_->c_str(), 1);
  else
    unsetenv("DISPLAY");
  kill(pid_, SIGTERM);
  int status = 0;
  waitpid(pid_, &status, 0);
}

}  // namespace grains::postprocess
