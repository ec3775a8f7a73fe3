#pragma once
// Files written by the output tests: scratch folders, the lines of a file and the cells of a CSV
// line.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace grain::test {

/// What scratch() leaves at the folder's place.
enum class Folder {
  absent, ///< nothing: the writer under test creates the folder
  empty   ///< an empty folder
};

/// The folder `folder` under the temporary directory, removed with everything in it and, with
/// Folder::empty, created again.
inline std::filesystem::path scratch(const std::filesystem::path& folder,
                                     Folder state = Folder::absent) {
  const auto dir = std::filesystem::temp_directory_path() / folder;
  std::filesystem::remove_all(dir);
  if (state == Folder::empty) std::filesystem::create_directories(dir);
  return dir;
}

/// The lines of a text file, without their line ends.
inline std::vector<std::string> lines_of(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);)
    lines.push_back(l);
  return lines;
}

/// The cells of one CSV line, split at every comma (no quoting).
inline std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ','))
    out.push_back(cell);
  return out;
}

} // namespace grain::test
