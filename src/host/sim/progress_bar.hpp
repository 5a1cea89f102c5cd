#pragma once
// A progress bar for long runs: redrawn in place on a terminal (stderr), nothing otherwise (a log
// or a file gets the results, not a line per update).

#include <iosfwd>
#include <string>

namespace comply::host {

class ProgressBar {
 public:
  /// `out` nullptr: silent. `total` in the caller's unit (simulated seconds).
  ProgressBar(std::ostream* out, std::string label, double total);
  /// `done` of `total`; `wall_s` since the start, for the speed figure.
  void update(double done, double wall_s);
  /// Completes the line.
  void finish();

 private:
  void draw(double done, double wall_s);

  std::ostream* out_;
  std::string label_;
  double total_;
  bool terminal_;
  int last_percent_ = -1;
  bool finished_ = false;
};

}  // namespace comply::host
