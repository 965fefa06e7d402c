#pragma once
// What every loader promises on any input, however hostile (the fuzz targets in tests/fuzz/ and
// the corpus replay in tests/scene/fuzz_corpus_test.cpp check it): it either returns a scene whose
// indices and sizes are consistent and whose geometry is finite, or throws one exception whose
// message is one line starting with the file's name. Anything else -- another exception type, a
// message without the name, a crash, a sanitizer report -- is a bug.
#include "scene/scene.h"

#include <functional>
#include <string>

namespace pt::test {

// "" when `scene` is consistent, else the first inconsistency found.
std::string sceneInconsistency(const Scene& scene);

// "" when the message is "<displayName>: <problem>" on one line (the problem bounded in length),
// else what is wrong with it.
std::string messageProblem(const std::string& message, const std::string& displayName);

// Runs `load` and returns "" when it kept the contract, else what it broke.
std::string checkLoadContract(const std::string& displayName, const std::function<Scene()>& load);

} // namespace pt::test
