#include "sweep_progress.hpp"

#include <spdlog/spdlog.h>

#include <unistd.h>

#include <cstdio>
#include <string>

namespace mechgraph::cli {
namespace {

std::string duration_text(double seconds) {
  char buffer[32];
  const long s = static_cast<long>(seconds + 0.5);
  if (s >= 3600) std::snprintf(buffer, sizeof buffer, "%ld:%02ld:%02ld", s / 3600, s / 60 % 60, s % 60);
  else std::snprintf(buffer, sizeof buffer, "%ld:%02ld", s / 60, s % 60);
  return buffer;
}

}  // namespace

SweepProgress::SweepProgress(std::size_t total, bool enabled)
    : total_(total), enabled_(enabled), terminal_(isatty(STDERR_FILENO) == 1),
      start_(std::chrono::steady_clock::now()), last_(start_) {}

void SweepProgress::update(std::size_t done, std::size_t failed) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const double since = std::chrono::duration<double>(now - last_).count();
  if (since < (terminal_ ? 0.1 : 5.0)) return;
  last_ = now;
  draw(done, failed, false);
}

void SweepProgress::finish(std::size_t done, std::size_t failed) {
  if (!enabled_ || !terminal_) return;
  draw(done, failed, true);
}

void SweepProgress::draw(std::size_t done, std::size_t failed, bool final) {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = elapsed > 0 ? static_cast<double>(done) / elapsed : 0.0;
  const std::string left = rate > 0 ? duration_text(static_cast<double>(total_ - done) / rate) + " left" : "";
  char failures[48] = "";
  if (failed) std::snprintf(failures, sizeof failures, " (%zu failed)", failed);
  if (terminal_) {
    constexpr int width = 30;
    const int filled = total_ ? static_cast<int>(width * done / total_) : width;
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r\033[K%zu/%zu cases%s [%s] %.4g/s %s%s", done, total_, failures, bar.c_str(), rate,
                 final ? duration_text(elapsed).c_str() : left.c_str(), final ? "\n" : "");
    std::fflush(stderr);
  } else {
    spdlog::info("sweep: {}/{} cases{}, {:.4g}/s, {}", done, total_, failures, rate, left);
  }
}

}  // namespace mechgraph::cli
