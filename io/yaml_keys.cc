#include "io/yaml_keys.h"

#include <algorithm>
#include <map>
#include <sstream>

#include <yaml-cpp/yaml.h>

namespace sacfuse {

std::vector<YamlRepeatedKey> RepeatedYamlKeys(const YAML::Node& map) {
  std::vector<YamlRepeatedKey> repeats;
  if (!map.IsMap()) return repeats;
  std::map<std::string, int> first_lines;
  size_t index = 0;
  for (const auto& kv : map) {
    const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : YAML::Dump(kv.first);
    const int line = kv.first.Mark().line + 1;
    const auto [it, fresh] = first_lines.emplace(key, line);
    if (!fresh) repeats.push_back({key, index, line, it->second});
    ++index;
  }
  return repeats;
}

std::string RepeatedYamlKeyProblem(const YamlRepeatedKey& repeat) {
  return "duplicate key (first on line " + std::to_string(repeat.first_line) +
         "); YAML keeps only one of them: remove or merge the other";
}

namespace {

// Whether a line is a document start marker: "---" at column 0, then the end of the line or white space.
bool IsDocumentStart(const std::string& line) {
  return line.compare(0, 3, "---") == 0 && (line.size() == 3 || line[3] == ' ' || line[3] == '\t' ||
                                             line[3] == '\r');
}

}  // namespace

YAML::Node LoadOneYamlDocument(const std::string& text, int* second_document_line) {
  *second_document_line = 0;
  const std::vector<YAML::Node> documents = YAML::LoadAll(text);
  if (documents.empty()) return YAML::Node();
  size_t second = 1;
  while (second < documents.size() && documents[second].IsNull()) ++second;
  if (second == documents.size()) return documents[0];
  // The "---" line before the second document's content (its mark), or its content's line.
  const int content_line = documents[second].Mark().line;  // 0-based; -1 when unknown
  const int first_line = documents[0].IsNull() ? -1 : documents[0].Mark().line;
  std::istringstream lines(text);
  std::string line;
  int marker = -1;
  for (int n = 0; std::getline(lines, line); ++n) {
    if (content_line >= 0 && n > content_line) break;
    if (IsDocumentStart(line) && n > first_line) {
      marker = n;
      if (content_line < 0) break;
    }
  }
  *second_document_line = (marker >= 0 ? marker : std::max(content_line, 0)) + 1;
  return documents[0];
}

std::string YamlSecondDocumentProblem(const std::string& what) {
  return "a second YAML document starts here (a \"---\" line); " + what +
         " holds one document, and YAML readers ignore the keys after \"---\": put them into the first document";
}

}  // namespace sacfuse
