#include "progress_bar.hpp"

#include <unistd.h>

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <ostream>

namespace comply::host {

ProgressBar::ProgressBar(std::ostream* out, std::string label, double total)
    : out_(out),
      label_(std::move(label)),
      total_(total),
      // Only stderr is known to be a terminal; any other stream is treated as a log.
      terminal_(out == &std::cerr && isatty(STDERR_FILENO) != 0) {}

void ProgressBar::update(double done, double wall_s) {
  // Only on a terminal: in a log, a line per update is noise between the lines that matter.
  if (out_ == nullptr || !terminal_ || finished_ || total_ <= 0.0) {
    return;
  }
  const int percent = std::clamp(static_cast<int>(100.0 * done / total_), 0, 100);
  if (percent == last_percent_) {
    return;
  }
  last_percent_ = percent;
  draw(done, wall_s);
}

void ProgressBar::draw(double done, double wall_s) {
  constexpr int kWidth = 30;
  const int filled = kWidth * last_percent_ / 100;
  std::ostream& out = *out_;
  out << "\r" << label_ << " [" << std::string(filled, '#')
      << std::string(kWidth - filled, '.') << "] " << std::setw(3) << last_percent_ << "%  "
      << std::fixed << std::setprecision(2) << done << "/" << total_ << " s";
  if (wall_s > 0.0) {
    out << "  " << std::setprecision(1) << done / wall_s << "x real time";
  }
  out << std::flush;
}

void ProgressBar::finish() {
  if (out_ != nullptr && !finished_ && terminal_) {
    *out_ << "\n";
  }
  finished_ = true;
}

}  // namespace comply::host
