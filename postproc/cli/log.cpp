#include "postproc/cli/log.h"

#include <spdlog/details/null_mutex.h>
#include <spdlog/sinks/base_sink.h>

#include <iostream>
#include <memory>
#include <string>

namespace vcpost::cli {
namespace {

// One line per message on std::cerr, after the "vcpost: " prefix and the
// level's word: the same stream as the lines written without the logger,
// so they keep their order.
class StderrLines final : public spdlog::sinks::base_sink<spdlog::details::null_mutex> {
 protected:
  void sink_it_(const spdlog::details::log_msg& message) override {
    std::string line = "vcpost: ";
    if (message.level == spdlog::level::warn) line += "warning: ";
    if (message.level <= spdlog::level::debug) line += "debug: ";
    line.append(message.payload.data(), message.payload.size());
    line += '\n';
    std::cerr << line;
  }
  void flush_() override { std::cerr.flush(); }
};

std::shared_ptr<spdlog::logger> make_logger() {
  auto logger = std::make_shared<spdlog::logger>("vcpost", std::make_shared<StderrLines>());
  logger->set_level(spdlog::level::info);
  return logger;
}

}  // namespace

spdlog::logger& log() {
  static const std::shared_ptr<spdlog::logger> logger = make_logger();
  return *logger;
}

std::optional<spdlog::level::level_enum> parse_log_level(std::string_view name) {
  if (name == "error") return spdlog::level::err;
  if (name == "warning") return spdlog::level::warn;
  if (name == "info") return spdlog::level::info;
  if (name == "debug") return spdlog::level::debug;
  return std::nullopt;
}

void set_log_level(spdlog::level::level_enum level) { log().set_level(level); }

}  // namespace vcpost::cli
