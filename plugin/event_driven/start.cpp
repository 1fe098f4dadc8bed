#include "start.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

namespace mn {
namespace ed {

namespace {

double number(const std::string &word, const std::string &what, const std::string &where)
{
  char *end = nullptr;
  const double v = std::strtod(word.c_str(), &end);
  if (word.empty() || *end != '\0') throw InputError(where + ": " + what + " '" + word + "' is not a number");
  if (!std::isfinite(v)) throw InputError(where + ": " + what + " is " + word + ": it must be finite");
  return v;
}

}    // namespace

Start read_start(const std::string &path)
{
  std::ifstream in(path);
  if (!in) throw InputError("cannot open the start file '" + path + "'");
  Start start;
  start.origin = path;
  bool has_box = false;
  std::string line;
  for (int number_of_line = 1; std::getline(in, line); number_of_line++) {
    const std::string where = path + " line " + std::to_string(number_of_line);
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string word; words >> word;) w.push_back(word);
    if (w.empty()) continue;
    auto expect = [&](std::size_t values, const char *form) {
      if (w.size() != values + 1)
        throw InputError(where + ": '" + w[0] + "' takes " + std::to_string(values) +
                         " values (" + form + "), not " + std::to_string(w.size() - 1));
    };
    if (w[0] == "box") {
      expect(2, "box XLO XHI");
      if (has_box) throw InputError(where + ": a second 'box' line");
      start.xlo = number(w[1], "XLO", where);
      start.xhi = number(w[2], "XHI", where);
      if (!(start.xhi > start.xlo))
        throw InputError(where + ": box XHI = " + w[2] + " must be greater than XLO = " + w[1]);
      has_box = true;
    } else if (w[0] == "floor") {
      expect(1, "floor Y");
      if (start.has_floor) throw InputError(where + ": a second 'floor' line");
      start.has_floor = true;
      start.floor_y = number(w[1], "Y", where);
    } else if (w[0] == "disk") {
      expect(6, "disk X Y VX VY OMEGA DIAMETER");
      StartDisk d{number(w[1], "X", where),  number(w[2], "Y", where),
                  number(w[3], "VX", where), number(w[4], "VY", where),
                  number(w[5], "OMEGA", where), number(w[6], "DIAMETER", where), where};
      if (!(d.diameter > 0.0)) throw InputError(where + ": DIAMETER = " + w[6] + " must be > 0");
      start.disks.push_back(d);
    } else if (w[0] == "bump") {
      expect(3, "bump X Y DIAMETER");
      Bump b{number(w[1], "X", where), number(w[2], "Y", where), number(w[3], "DIAMETER", where),
             where};
      if (!(b.diameter > 0.0)) throw InputError(where + ": DIAMETER = " + w[3] + " must be > 0");
      start.bumps.push_back(b);
    } else {
      throw InputError(where + ": unknown line '" + w[0] +
                       "' (a start file has box, floor, disk and bump lines)");
    }
  }
  if (!has_box) throw InputError(path + ": no 'box XLO XHI' line");
  return start;
}

}    // namespace ed
}    // namespace mn
