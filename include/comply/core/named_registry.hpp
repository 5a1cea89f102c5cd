#pragma once
// Factories by name, safe to use from any thread: what `--transport NAME` and `--hardware NAME`
// pick from. Registration happens at start-up; look-ups are rare (once per host).

#include <map>
#include <mutex>
#include <string>
#include <vector>

namespace comply {

template <typename Factory>
class NamedRegistry {
 public:
  explicit NamedRegistry(std::map<std::string, Factory> initial = {})
      : factories_(std::move(initial)) {}

  /// Adds `factory` under `name`, replacing one of that name.
  void add(const std::string& name, Factory factory) {
    const std::lock_guard<std::mutex> lock(mutex_);
    factories_[name] = std::move(factory);
  }
  /// The factory registered as `name`; an empty one when there is none.
  [[nodiscard]] Factory find(const std::string& name) const {
    const std::lock_guard<std::mutex> lock(mutex_);
    const auto found = factories_.find(name);
    return found == factories_.end() ? Factory{} : found->second;
  }
  /// The registered names, sorted, comma-separated (for "registered: ..." in errors).
  [[nodiscard]] std::string list() const {
    std::string text;
    for (const std::string& name : names()) {
      text += (text.empty() ? "" : ", ") + name;
    }
    return text;
  }
  [[nodiscard]] std::vector<std::string> names() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    std::vector<std::string> result;
    for (const auto& entry : factories_) {
      result.push_back(entry.first);
    }
    return result;
  }

 private:
  mutable std::mutex mutex_;
  std::map<std::string, Factory> factories_;
};

}  // namespace comply
