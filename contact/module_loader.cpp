#include "contact/module_loader.hpp"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace grains {

namespace {

void* load_symbol(const ModuleSpec& spec) {
  std::vector<std::string> tried;
  if (const char* env = std::getenv(spec.env_var); env && *env) {
    tried.emplace_back(env);  // the user's choice, and only it
  } else {
    if (spec.build_path && *spec.build_path) tried.emplace_back(spec.build_path);
    std::error_code ec;
    const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) tried.push_back((exe.parent_path() / spec.file_name).string());
    tried.emplace_back(spec.file_name);
  }
  std::string why;
  for (const auto& path : tried) {
    void* h = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!h) {
      const char* e = dlerror();
      why += "\n  " + path + ": " + (e ? e : "cannot be loaded");
      continue;
    }
    if (void* fn = dlsym(h, spec.symbol)) return fn;  // kept loaded to the end of the process
    why += "\n  " + path + ": has no " + spec.symbol;
    dlclose(h);
  }
  throw std::runtime_error(std::string(spec.needed_for) + " needs grains's " + spec.what + " module (" +
                           spec.file_name + ", built beside the grains program), which could not be loaded; set " +
                           spec.env_var + " to its path. Tried:" + why);
}

}  // namespace

void* module_symbol(const ModuleSpec& spec) {
  struct Entry {
    void* fn = nullptr;
    std::string failure;
  };
  static std::mutex m;
  static std::map<std::string, Entry> entries;
  const std::lock_guard<std::mutex> lock(m);
  const std::string key = std::string(spec.file_name) + ':' + spec.symbol;
  auto it = entries.find(key);
  if (it == entries.end()) {
    Entry e;
    try {
      e.fn = load_symbol(spec);
    } catch (const std::runtime_error& x) {
      e.failure = x.what();
    }
    it = entries.emplace(key, std::move(e)).first;
  }
  if (!it->second.fn) throw std::runtime_error(it->second.failure);
  return it->second.fn;
}

}  // namespace grains
