// Test helper: a strict little XML reader (well-formedness: nesting, quoting, one root, no stray
// text outside it) and the checks that make an XDMF file usable by ParaView's readers — every
// HDF DataItem names an existing dataset of exactly the declared dimensions, connectivity indexes
// existing points, attributes have one row per point. Shared by tests/modes and the CLI test helper
// (tests/cli/helpers/compare_modes.cpp). Returns a list of problems; empty means valid.
#pragma once

#include <Eigen/Core>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "common/hdf5_file.hpp"

namespace mastrom::testing_xdmf {

struct Element {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;
  std::vector<std::unique_ptr<Element>> children;
};

/// Parse `xml`; on failure returns null and sets `error`.
inline std::unique_ptr<Element> parseXml(const std::string& xml, std::string& error) {
  std::size_t i = 0;
  const std::size_t n = xml.size();
  std::vector<Element*> stack;
  std::unique_ptr<Element> root;
  const auto fail = [&](const std::string& what) {
    error = what + " at offset " + std::to_string(i);
    return nullptr;
  };
  const auto skipSpace = [&] {
    while (i < n && std::isspace(static_cast<unsigned char>(xml[i]))) ++i;
  };
  while (i < n) {
    if (xml[i] != '<') {
      const std::size_t next = xml.find('<', i);
      const std::string text = xml.substr(i, next == std::string::npos ? n - i : next - i);
      if (stack.empty()) {
        for (char c : text)
          if (!std::isspace(static_cast<unsigned char>(c))) return fail("text outside the root");
      } else {
        stack.back()->text += text;
      }
      i = next == std::string::npos ? n : next;
      continue;
    }
    if (xml.compare(i, 4, "<!--") == 0) {
      const std::size_t end = xml.find("-->", i + 4);
      if (end == std::string::npos) return fail("unterminated comment");
      i = end + 3;
      continue;
    }
    if (xml.compare(i, 2, "<?") == 0) {
      const std::size_t end = xml.find("?>", i + 2);
      if (end == std::string::npos || root || !stack.empty())
        return fail("misplaced or unterminated processing instruction");
      i = end + 2;
      continue;
    }
    if (xml.compare(i, 9, "<!DOCTYPE") == 0) {
      if (root || !stack.empty()) return fail("misplaced DOCTYPE");
      std::size_t j = i + 9;
      int depth = 0;
      while (j < n && (xml[j] != '>' || depth > 0)) {
        if (xml[j] == '[') ++depth;
        if (xml[j] == ']') --depth;
        ++j;
      }
      if (j >= n) return fail("unterminated DOCTYPE");
      i = j + 1;
      continue;
    }
    if (xml.compare(i, 2, "</") == 0) {
      i += 2;
      const std::size_t start = i;
      while (i < n && (std::isalnum(static_cast<unsigned char>(xml[i])) || xml[i] == '_' ||
                       xml[i] == '-' || xml[i] == ':' || xml[i] == '.'))
        ++i;
      const std::string name = xml.substr(start, i - start);
      skipSpace();
      if (i >= n || xml[i] != '>') return fail("malformed end tag");
      ++i;
      if (stack.empty() || stack.back()->name != name)
        return fail("end tag </" + name + "> does not match the open element");
      stack.pop_back();
      continue;
    }
    // Start tag.
    ++i;
    const std::size_t start = i;
    while (i < n && (std::isalnum(static_cast<unsigned char>(xml[i])) || xml[i] == '_' ||
                     xml[i] == '-' || xml[i] == ':' || xml[i] == '.'))
      ++i;
    auto element = std::make_unique<Element>();
    element->name = xml.substr(start, i - start);
    if (element->name.empty()) return fail("empty element name");
    bool self_closing = false;
    while (true) {
      skipSpace();
      if (i >= n) return fail("unterminated start tag");
      if (xml[i] == '>') {
        ++i;
        break;
      }
      if (xml.compare(i, 2, "/>") == 0) {
        i += 2;
        self_closing = true;
        break;
      }
      const std::size_t a = i;
      while (i < n && xml[i] != '=' && !std::isspace(static_cast<unsigned char>(xml[i]))) ++i;
      const std::string key = xml.substr(a, i - a);
      skipSpace();
      if (i >= n || xml[i] != '=') return fail("attribute without value");
      ++i;
      skipSpace();
      if (i >= n || (xml[i] != '"' && xml[i] != '\'')) return fail("unquoted attribute value");
      const char quote = xml[i++];
      const std::size_t end = xml.find(quote, i);
      if (end == std::string::npos) return fail("unterminated attribute value");
      const std::string value = xml.substr(i, end - i);
      if (value.find('<') != std::string::npos) return fail("'<' in an attribute value");
      if (element->attributes.count(key)) return fail("duplicate attribute " + key);
      element->attributes[key] = value;
      i = end + 1;
    }
    Element* raw = element.get();
    if (stack.empty()) {
      if (root) return fail("second root element");
      root = std::move(element);
    } else {
      stack.back()->children.push_back(std::move(element));
    }
    if (!self_closing) stack.push_back(raw);
  }
  if (!stack.empty()) return fail("unclosed element <" + stack.back()->name + ">");
  if (!root) return fail("no root element");
  return root;
}

inline std::string trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t\r\n");
  const std::size_t b = s.find_last_not_of(" \t\r\n");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

inline void collect(const Element& e, const std::string& name, std::vector<const Element*>& out) {
  if (e.name == name) out.push_back(&e);
  for (const auto& c : e.children) collect(*c, name, out);
}

/// Every check of the header on the XDMF file at `path`; `grids` receives the number of grids
/// that carry a topology.
inline std::vector<std::string> checkXdmf(const std::string& path, int* grids = nullptr) {
  std::vector<std::string> problems;
  std::ifstream in(path);
  if (!in) return {"cannot read " + path};
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string error;
  const std::unique_ptr<Element> root = parseXml(buffer.str(), error);
  if (!root) return {"not well-formed XML: " + error};
  if (root->name != "Xdmf") problems.push_back("root element is <" + root->name + ">");
  const std::filesystem::path directory = std::filesystem::path(path).parent_path();

  std::vector<const Element*> uniform;
  collect(*root, "Grid", uniform);
  int counted = 0;
  for (const Element* grid : uniform) {
    const Element* topology = nullptr;
    const Element* geometry = nullptr;
    std::vector<const Element*> attributes;
    for (const auto& c : grid->children) {
      if (c->name == "Topology") topology = c.get();
      if (c->name == "Geometry") geometry = c.get();
      if (c->name == "Attribute") attributes.push_back(c.get());
    }
    if (!topology) continue;
    ++counted;
    const std::string where =
        "grid '" +
        (grid->attributes.count("Name") ? grid->attributes.at("Name") : std::string("?")) + "'";
    if (!geometry) {
      problems.push_back(where + ": no Geometry");
      continue;
    }
    // Every data item: an existing dataset of the declared dimensions.
    std::map<const Element*, Eigen::MatrixXd> data;
    std::vector<const Element*> items;
    collect(*grid, "DataItem", items);
    for (const Element* item : items) {
      const std::string text = trim(item->text);
      const std::size_t colon = text.find(':');
      if (item->attributes.count("Format") == 0 || item->attributes.at("Format") != "HDF" ||
          colon == std::string::npos) {
        problems.push_back(where + ": DataItem '" + text + "' is not an HDF reference");
        continue;
      }
      const std::string file = (directory / text.substr(0, colon)).string();
      const std::string dataset = text.substr(colon + 1);
      try {
        const h5::File h5 = h5::File::open(file, h5::OpenMode::ReadOnly);
        if (!h5.exists(dataset)) {
          problems.push_back(where + ": dataset " + dataset + " missing in " + file);
          continue;
        }
        std::vector<std::size_t> shape = h5.datasetShape(dataset);
        std::istringstream dims(
            item->attributes.count("Dimensions") ? item->attributes.at("Dimensions") : "");
        std::vector<std::size_t> declared;
        std::size_t d = 0;
        while (dims >> d) declared.push_back(d);
        if (declared != shape)
          problems.push_back(where + ": " + dataset + " has other dimensions than declared");
        data[item] = h5.readMatrix(dataset);
      } catch (const std::exception& e) {
        problems.push_back(where + ": " + e.what());
      }
    }
    // Topology indexes existing points; attributes have one row per point.
    Eigen::Index points = -1;
    for (const auto& c : geometry->children)
      if (data.count(c.get())) points = data[c.get()].rows();
    for (const auto& c : topology->children) {
      if (!data.count(c.get())) continue;
      const Eigen::MatrixXd& cells = data[c.get()];
      const std::string count = topology->attributes.count("NumberOfElements")
                                    ? topology->attributes.at("NumberOfElements")
                                    : "";
      if (count != std::to_string(cells.rows()))
        problems.push_back(where + ": NumberOfElements differs from the connectivity rows");
      if (cells.size() > 0 && (cells.minCoeff() < 0 || cells.maxCoeff() >= double(points)))
        problems.push_back(where + ": connectivity indexes a missing point");
    }
    for (const Element* attribute : attributes)
      for (const auto& c : attribute->children)
        if (data.count(c.get()) && data[c.get()].rows() != points)
          problems.push_back(where + ": attribute rows differ from the point count");
  }
  if (grids) *grids = counted;
  return problems;
}

}  // namespace mastrom::testing_xdmf
