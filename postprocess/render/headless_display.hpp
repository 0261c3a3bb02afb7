#pragma once
// An X display for VTK's GLX render windows on a headless machine: when
// DISPLAY is unset or cannot be opened, starts `Xvfb -displayfd` (it picks a
// free display number and reports it), waits until a client can connect,
// and points DISPLAY at it until the guard is destroyed (then restores it).
// VTK aborts the process when it cannot open its display; this guard throws
// instead.
#include <optional>
#include <string>
#include <sys/types.h>

namespace grains::postprocess {

class HeadlessDisplay {
 public:
  /// Throws std::runtime_error when there is no usable DISPLAY and Xvfb
  /// cannot start or cannot be connected to.
  HeadlessDisplay();
  ~HeadlessDisplay();
  HeadlessDisplay(const HeadlessDisplay&) = delete;
  HeadlessDisplay& operator=(const HeadlessDisplay&) = delete;
  /// The display in use (":0", ":99", ...).
  const std::string& display() const { return display_; }
  /// True when this guard started its own Xvfb.
  bool started_xvfb() const { return pid_ > 0; }

 private:
  std::string display_;
  pid_t pid_ = -1;
  std::optional<std::string> previous_;  // DISPLAY before this guard replaced it
};

}  // namespace grains::postprocess
