// scene_keys_doc: prints docs/scene_keys.md from the scene schema table and the law registry.
//   scene_keys_doc               the document, on standard output
//   scene_keys_doc --check FILE  exit 1 (and say how to regenerate) when FILE differs from it
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "io/scene/scene_schema.hpp"

int main(int argc, char** argv) {
  const std::string doc = raceway::scene::schema::scene_keys_markdown();
  if (argc == 1) {
    std::cout << doc;
    return 0;
  }
  if (argc != 3 || std::string(argv[1]) != "--check") {
    std::cerr << "usage: scene_keys_doc [--check FILE]\n";
    return 2;
  }
  std::ifstream in(argv[2], std::ios::binary);
  std::ostringstream committed;
  committed << in.rdbuf();
  if (in && committed.str() == doc) return 0;
  std::cerr << argv[2] << " is out of date with the scene schema (io/scene/scene_schema.cpp) or the law registry; "
            << "run: scene_keys_doc > docs/scene_keys.md\n";
  return 1;
}
