#pragma once
// A small reader of the VTK files pradis writes (io/vtk_series.hpp), for the
// tests: the numbers of a DataArray, the attributes of the elements of a tag.

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "testing/test_support.hpp"

namespace vtk_test {
using pradis_test::slurp;
/// The numbers inside the first <DataArray ... Name="name" ...> element.
inline std::vector<double> data_array(const std::string& xml, const std::string& name) {
  const std::size_t at = xml.find("Name=\"" + name + "\"");
  REQUIRE(at != std::string::npos);
  const std::size_t open = xml.find('>', at) + 1, close = xml.find("</DataArray>", open);
  std::istringstream in(xml.substr(open, close - open));
  std::vector<double> v;
  for (double x; in >> x;) v.push_back(x);
  return v;
}
/// The value of attribute `key` in every element <tag .../> of xml.
inline std::vector<std::string> attributes(const std::string& xml, const std::string& tag, const std::string& key) {
  std::vector<std::string> out;
  for (std::size_t at = xml.find("<" + tag + " "); at != std::string::npos; at = xml.find("<" + tag + " ", at + 1)) {
    const std::size_t end = xml.find('>', at), k = xml.find(key + "=\"", at);
    REQUIRE(k < end);
    const std::size_t v = k + key.size() + 2;
    out.push_back(xml.substr(v, xml.find('"', v) - v));
  }
  return out;
}
inline int attribute_int(const std::string& xml, const std::string& key) {
  const auto v = attributes(xml, "Piece", key);
  REQUIRE(v.size() == 1);
  return std::stoi(v[0]);
}
}  // namespace vtk_test
