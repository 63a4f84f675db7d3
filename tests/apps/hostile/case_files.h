#pragma once
// The files of a catalogue case, created in its scratch folder, and a snapshot of a
// folder's entries to tell afterwards what a run created, changed or replaced.

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <map>
#include <string>

namespace gplanner::hostile {

// Writes the fixtures every case starts from into `folder`: cube.obj (a 0.2 m cube),
// scene.yaml (the cube as a rigid robot beside a wall in a box), arm.urdf, arm.srdf and
// arm.yaml (a two-joint arm on a fixed base).
void write_fixtures(const std::string& folder);

// Creates `name` in `folder` as `spec` says (see catalogue.yaml: inline text, repeated
// text, hex bytes, sparse files, FIFOs, symlinks, hard links, folders, URDF chains, device nodes, read-only
// modes, fixtures edited by replacement, roadmap files saved for a scene and edited).
// Throws std::runtime_error when the file cannot be made.
void create_file(const std::string& folder, const std::string& name, const YAML::Node& spec);

// What an entry is, enough to tell whether it changed.
struct EntryState {
  char type = '?';  // f regular, d folder, l symlink, p FIFO, c/b device, s socket
  std::uintmax_t size = 0;
  std::int64_t mtime_ns = 0;
  unsigned mode = 0;
  std::uint64_t content = 0;  // a hash of a regular file's bytes (first and last MiB when big)
  std::string link_target;
  bool operator==(const EntryState& o) const {
    return type == o.type && size == o.size && mtime_ns == o.mtime_ns && mode == o.mode &&
           content == o.content && link_target == o.link_target;
  }
};

// Every entry under `folder` (symlinks not followed), by path relative to it.
std::map<std::string, EntryState> snapshot(const std::string& folder);

// One entry, or type '-' when it does not exist.
EntryState entry_state(const std::string& path);

// Makes `user` (and the group of that number) own `folder` and everything in it
// (symlinks themselves), modes unchanged.
void give_to(const std::string& folder, int user);

// Gives the owner write permission on every folder below `folder` again (read-only
// folders made by a case), so that it can be removed.
void make_removable(const std::string& folder);

}  // namespace gplanner::hostile
