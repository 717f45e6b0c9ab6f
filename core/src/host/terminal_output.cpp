#include <mechgraph/host/terminal_output.hpp>

#include <mechgraph/text_escape.hpp>

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <iostream>
#include <memory>
#include <utility>

namespace mechgraph::host {
namespace {

class TerminalSafeSink final : public spdlog::sinks::sink {
 public:
  explicit TerminalSafeSink(spdlog::sink_ptr inner) : inner_(std::move(inner)) {}

  void log(const spdlog::details::log_msg& message) override {
    const std::string safe = terminal_text(std::string_view(message.payload.data(), message.payload.size()));
    spdlog::details::log_msg shown = message;
    shown.payload = spdlog::string_view_t(safe.data(), safe.size());
    inner_->log(shown);
  }
  void flush() override { inner_->flush(); }
  void set_pattern(const std::string& pattern) override { inner_->set_pattern(pattern); }
  void set_formatter(std::unique_ptr<spdlog::formatter> formatter) override { inner_->set_formatter(std::move(formatter)); }

 private:
  spdlog::sink_ptr inner_;
};

}  // namespace

void print_text(std::string_view text) { std::cout << terminal_text(text); }

spdlog::sink_ptr terminal_safe_sink(spdlog::sink_ptr inner) { return std::make_shared<TerminalSafeSink>(std::move(inner)); }

void use_terminal_safe_logger(const char* name) {
  auto sink = terminal_safe_sink(std::make_shared<spdlog::sinks::stderr_color_sink_mt>());
  auto logger = std::make_shared<spdlog::logger>(name, std::move(sink));
  spdlog::set_default_logger(std::move(logger));
}

}  // namespace mechgraph::host
