#pragma once
/// \file
/// The diagnostics log: the role of PRADIS's SYSPRINT.TXT. Kernel and elements
/// write warnings and the text of every error here; the user points it at a
/// stream or a file, or leaves it silent (the default).

#include <fstream>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <string_view>

#include "pradis/core/error.hpp"

namespace pradis {

/// Destination of diagnostic messages. Silent until to() or to_file() is called.
class diagnostics {
 public:
  /// Sends messages to `os` (which must outlive this object).
  void to(std::ostream& os) {
    silence();
    os_ = &os;
  }
  /// Hands each message to `sink` (e.g. a model-language session, which shows the
  /// warnings among its own report lines).
  void to(std::function<void(std::string_view)> sink) {
    silence();
    sink_ = std::move(sink);
  }
  /// Sends messages to a file (created or truncated), e.g. "SYSPRINT.TXT".
  void to_file(const std::string& path) {
    auto f = std::make_unique<std::ofstream>(path);
    if (!*f) throw error(error_code::io_error, "cannot open diagnostics file '" + path + "'");
    silence();
    os_ = f.get();
    file_ = std::move(f);
  }
  /// Stops writing anywhere.
  void silence() {
    file_.reset();
    os_ = nullptr;
    sink_ = nullptr;
  }
  /// Writes one line, unless silent.
  void write(std::string_view line) {
    if (os_) {
      *os_ << line << '\n';
      os_->flush();
    }
    if (sink_) sink_(line);
  }
  /// Writes the text of an error.
  void write(const error& e) { write(std::string_view(e.what())); }
  /// Whether messages go anywhere.
  bool active() const noexcept { return os_ != nullptr || sink_ != nullptr; }

 private:
  std::ostream* os_ = nullptr;
  std::unique_ptr<std::ofstream> file_;
  std::function<void(std::string_view)> sink_;
};

}  // namespace pradis
