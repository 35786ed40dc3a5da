#include "experiment/run_metadata.h"

#include <cholmod.h>
#include <tbb/info.h>
#include <tbb/version.h>

#include <array>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <thread>

namespace fairshape {
namespace {

std::string run_command(const std::string& cmd) {
  std::array<char, 256> buf{};
  std::string out;
  FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return "";
  while (std::fgets(buf.data(), static_cast<int>(buf.size()), p)) out += buf.data();
  ::pclose(p);
  while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
  return out;
}

std::string cpu_model() {
  std::ifstream f("/proc/cpuinfo");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2);
  return "unknown";
}

std::string git(const std::string& args) {
  return run_command("git -C '" FAIRSHAPE_SOURCE_DIR "' " + args + " 2>/dev/null");
}

}  // namespace

nlohmann::json yaml_to_json(const YAML::Node& n) {
  if (!n.IsDefined() || n.IsNull()) return nullptr;
  if (n.IsSequence()) {
    auto a = nlohmann::json::array();
    for (const auto& v : n) a.push_back(yaml_to_json(v));
    return a;
  }
  if (n.IsMap()) {
    auto o = nlohmann::json::object();
    for (const auto& kv : n) o[kv.first.as<std::string>()] = yaml_to_json(kv.second);
    return o;
  }
  const std::string& s = n.Scalar();
  if (n.Tag() != "!") {  // unquoted scalars may be numbers or booleans
    long long i;
    double d;
    bool b;
    if (YAML::convert<long long>::decode(n, i)) return i;
    if (YAML::convert<double>::decode(n, d)) return d;
    if (YAML::convert<bool>::decode(n, b)) return b;
  }
  return s;
}

std::string git_short_sha() {
  const std::string sha = git("rev-parse --short=7 HEAD");
  return sha.empty() ? "nogit" : sha;
}

std::string utc_timestamp(const char* format) {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[64];
  std::strftime(buf, sizeof buf, format, &tm);
  return buf;
}

nlohmann::json build_and_machine_info() {
  nlohmann::json j;
  j["git_commit"] = git("rev-parse HEAD");
  j["git_dirty"] = !git("status --porcelain --untracked-files=no").empty();
  j["compiler"] = std::string(FAIRSHAPE_COMPILER_ID) + " " + __VERSION__;
  j["build_type"] = FAIRSHAPE_BUILD_TYPE;
  j["compiler_flags"] = FAIRSHAPE_CXX_FLAGS;
  j["libraries"] = {{"eigen", FAIRSHAPE_EIGEN_VERSION},
                    {"tbb", TBB_VERSION_STRING},
                    {"suitesparse_cholmod", std::to_string(CHOLMOD_MAIN_VERSION) + "." +
                                                std::to_string(CHOLMOD_SUB_VERSION) + "." +
                                                std::to_string(CHOLMOD_SUBSUB_VERSION)},
                    {"ceres", FAIRSHAPE_CERES_VERSION},
                    {"vtk", FAIRSHAPE_VTK_VERSION},
                    {"yaml_cpp", FAIRSHAPE_YAML_CPP_VERSION}};
  j["cpu_model"] = cpu_model();
  j["hardware_threads"] = std::thread::hardware_concurrency();
  j["tbb_default_concurrency"] = tbb::info::default_concurrency();
  return j;
}

}  // namespace fairshape
