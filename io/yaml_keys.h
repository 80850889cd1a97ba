#pragma once
// What yaml-cpp leaves silent in user YAML, for every reader of it (job configs, camera files): a second document
// and repeated keys.
// A second document: YAML::Load reads the first document of a stream only, so keys after a "---" line were silently
// ignored.
// Repeated keys in a YAML mapping. yaml-cpp keeps every pair of a mapping with a repeated key, but a lookup by key
// sees only one of them, so a repeat silently wins or loses; every reader of user YAML (job configs, camera
// files) refuses repeats through this one check.
#include <string>
#include <vector>

#include <yaml-cpp/node/node.h>

namespace sacfuse {

struct YamlRepeatedKey {
  std::string key;     // the scalar text of the key
  size_t index = 0;    // position of the repeat among the mapping's pairs (0-based)
  int line = 0;        // 1-based line of the repeat
  int first_line = 0;  // 1-based line of its first occurrence
};

// The repeats among the keys of `map`, in file order (empty for a node that is not a mapping).
std::vector<YamlRepeatedKey> RepeatedYamlKeys(const YAML::Node& map);

// "duplicate key (first on line N); YAML keeps only one of them: remove or merge the other"
std::string RepeatedYamlKeyProblem(const YamlRepeatedKey& repeat);

// The one document of a YAML text (a leading "---" and empty documents after it are allowed). Throws
// YAML::ParserException for text that is not YAML. *second_document_line (1-based) is set to the line of the
// "---" that opens a second document with content (where it starts when there is no such line), else to 0; the
// caller refuses it with its own error type, naming the file and that line (YamlSecondDocumentProblem).
YAML::Node LoadOneYamlDocument(const std::string& text, int* second_document_line);
// "a second YAML document starts here; a ... holds one document: ..."
std::string YamlSecondDocumentProblem(const std::string& what);

}  // namespace sacfuse
