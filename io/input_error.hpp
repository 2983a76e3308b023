#pragma once
#include <stdexcept>
#include <string>

namespace rigflex::io {

// Bad user input: names the file, the line (1-based, 0 if unknown) and the key
// or column. what() reads "file:line: key 'k': message".
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, int line, std::string key, const std::string& message);
  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& key() const { return key_; }
  const std::string& reason() const { return reason_; }

 private:
  std::string file_;
  int line_;
  std::string key_;
  std::string reason_;
};

}  // namespace rigflex::io
