#pragma once
// The file system as assimp sees it while it loads a mesh (private to the mesh loader):
// every file it opens, the mesh and whatever the mesh names (an OBJ's .mtl, textures,
// includes), goes through input_file_problem first.

#include <assimp/DefaultIOSystem.h>

#include <string>
#include <vector>

namespace gplanner {

class GuardedIOSystem : public Assimp::DefaultIOSystem {
 public:
  // A missing file is left to assimp (an OBJ without its .mtl loads without materials);
  // anything else that is not a readable regular file within the mesh size limit, and
  // any opening for writing, is refused: Open returns nullptr and refusal() says why.
  Assimp::IOStream* Open(const char* file, const char* mode = "rb") override;

  // Whether anything is at `file`, by stat alone (assimp's own opens it to see, and so
  // would wait forever on a FIFO).
  bool Exists(const char* file) const override;

  // The files opened, in order, each once.
  const std::vector<std::string>& files_read() const { return files_read_; }

  // "FILE PROBLEM" for the first file refused, or "".
  const std::string& refusal() const { return refusal_; }

 private:
  std::vector<std::string> files_read_;
  std::string refusal_;
};

}  // namespace gplanner
