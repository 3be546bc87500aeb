#include "fsi/io/output.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace fsi {

static std::string quote(const std::string &s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    if (c == '\n') {
      o += "\\n";
      continue;
    }
    o += c;
  }
  return o + "\"";
}

Json &Json::set(const std::string &k, double v) {
  char b[64];
  if (std::isfinite(v))
    std::snprintf(b, sizeof b, "%.10g", v);
  else
    std::snprintf(b, sizeof b, "null");
  items_.emplace_back(k, b);
  return *this;
}
Json &Json::set(const std::string &k, long v) {
  items_.emplace_back(k, std::to_string(v));
  return *this;
}
Json &Json::set(const std::string &k, bool v) {
  items_.emplace_back(k, v ? "true" : "false");
  return *this;
}
Json &Json::set(const std::string &k, const std::string &v) {
  items_.emplace_back(k, quote(v));
  return *this;
}
Json &Json::set(const std::string &k, const Json &v) {
  items_.emplace_back(k, "\x01" + v.str(0)); // marker: nested object, re-indented in str()
  return *this;
}
Json &Json::set(const std::string &k, const std::vector<std::string> &v) {
  std::string s = "[";
  for (size_t i = 0; i < v.size(); ++i)
    s += (i ? ", " : "") + quote(v[i]);
  items_.emplace_back(k, s + "]");
  return *this;
}

std::string Json::str(int indent) const {
  std::string pad(indent + 2, ' '), out = "{\n";
  for (size_t i = 0; i < items_.size(); ++i) {
    std::string v = items_[i].second;
    if (!v.empty() && v[0] == '\x01') { // nested: indent its lines
      v = v.substr(1);
      std::string r;
      for (char c : v)
        r += c == '\n' ? std::string("\n") + pad : std::string(1, c);
      v = r;
    }
    out += pad + quote(items_[i].first) + ": " + v + (i + 1 < items_.size() ? ",\n" : "\n");
  }
  return out + std::string(indent, ' ') + "}";
}

Output::Output(MPI_Comm comm, const std::string &dir) : comm_(comm), dir_(dir) {
  MPI_Comm_rank(comm, &rank_);
  int ok = 1;
  if (rank_ == 0) {
    std::string cmd = "mkdir -p '" + dir + "' 2>/dev/null";
    ok = std::system(cmd.c_str()) == 0 && access(dir.c_str(), W_OK) == 0;
    if (ok) {
      std::remove((dir + "/summary.json").c_str());
    }
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, comm);
  if (!ok)
    throw InputError("output directory " + dir +
                     " cannot be created or written: choose another -out_dir");
}

Output::~Output() {
  if (monitor_) std::fclose(monitor_);
}

// Collective: rank 0 writes; a failure (disk full, read-only directory) stops every rank.
void Output::write_atomic(const std::string &name, const std::string &content) const {
  collective_output(comm_, [&]() {
    if (rank_ != 0) return;
    const std::string path = dir_ + "/" + name, tmp = path + ".tmp";
    {
      std::ofstream f(tmp);
      f << content;
      f.close();
      if (!f) {
        std::remove(tmp.c_str());
        throw OutputError("cannot write " + tmp + " (disk full or directory not writable?)");
      }
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0)
      throw OutputError("cannot rename " + tmp + " to " + path);
  });
}

void Output::write_options() const {
  char *all = nullptr;
  FSI_CALL(PetscOptionsGetAll(nullptr, &all));
  std::string s(all ? all : "");
  FSI_CALL(PetscFree(all));
  // one option (with its values) per line
  std::string lines;
  std::stringstream ss(s);
  std::string tok, cur;
  while (ss >> tok) {
    if (tok[0] == '-' && !cur.empty() &&
        !(tok.size() > 1 && (std::isdigit(tok[1]) || tok[1] == '.'))) {
      lines += cur + "\n";
      cur.clear();
    }
    cur += (cur.empty() ? "" : " ") + tok;
  }
  if (!cur.empty()) lines += cur + "\n";
  write_atomic("options.txt", lines);
}

void Output::open_monitor(const std::vector<std::string> &columns, long resume_step) {
  if (rank_ != 0) return;
  std::string header = "step,time,newton,krylov,step_seconds";
  for (auto &c : columns)
    header += "," + c;
  // A resumed run keeps the rows up to its restart step from this directory's earlier run (the
  // partial file of a killed run is the newest), when that run had the same columns.
  std::vector<std::string> kept;
  const std::string csv = dir_ + "/monitor.csv", partial = csv + ".partial";
  if (resume_step >= 0) {
    std::ifstream old(access(partial.c_str(), R_OK) == 0 ? partial : csv);
    std::string line;
    if (std::getline(old, line) && line == header)
      while (std::getline(old, line))
        if (!line.empty() && std::atol(line.c_str()) <= resume_step) kept.push_back(line);
  }
  std::remove(csv.c_str());
  monitor_ = std::fopen(partial.c_str(), "w");
  if (!monitor_) throw InputError("cannot write " + partial);
  std::fprintf(monitor_, "%s\n", header.c_str());
  for (auto &l : kept)
    std::fprintf(monitor_, "%s\n", l.c_str());
}

// Collective (every rank calls it each step): a row that cannot be written stops every rank.
void Output::monitor_row(const std::vector<double> &v) {
  collective_output(comm_, [&]() {
    if (!monitor_) return;
    for (size_t i = 0; i < v.size(); ++i)
      std::fprintf(monitor_, i ? ",%.15g" : "%.15g", v[i]);
    std::fprintf(monitor_, "\n");
    if (std::fflush(monitor_) != 0 || std::ferror(monitor_))
      throw OutputError("cannot write " + dir_ + "/monitor.csv.partial (disk full?)");
  });
}

void Output::close_monitor() {
  if (!monitor_) return;
  const bool ok = std::fclose(monitor_) == 0;
  monitor_ = nullptr;
  // A monitor that could not be written whole stays .partial: never passed off as complete.
  if (ok) std::rename((dir_ + "/monitor.csv.partial").c_str(), (dir_ + "/monitor.csv").c_str());
}

void Output::write_summary(const Json &j) const {
  write_atomic("summary.json", j.str() + "\n");
}

} // namespace fsi
