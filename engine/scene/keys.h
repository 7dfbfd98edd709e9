#pragma once
// The scene keys: one declarative table (keys.cpp) of every key a scene file may hold, with its type,
// unit, default, bounds and meaning. The parser (scene.cpp) takes each key's default, bounds and
// allowed values from here and refuses a key the table does not list; docs/SCENES.md and
// media/scenes/scene.schema.json are generated from it (`ranryu scenes --markdown`, `--schema`), and
// tests/unit/scene_keys_test.cpp fails when the committed copies differ from what the table gives.
//
// Adding a key: one line in keys.cpp (in its object's group), one read of it in scene.cpp's parse(),
// then regenerate the two files (`cmake --build build/test --target scene-docs`).
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace ranryu::scene {

enum class KeyType {
    object,    // {...} of further keys
    objects,   // [{...}, ...]: its items' keys are listed under "PATH[]."
    number,    // a finite number in [lo, hi]
    integer,   // a whole number in [lo, hi]
    boolean,
    string,    // one of `choices`, or any string when there are none
    vec3,      // [x, y, z], each in [lo, hi]
    int_pair,  // [a, b], whole numbers in [lo, hi], a <= b
};
const char* key_type_name(KeyType t);

struct Key {
    std::string path;       // dotted from the root; "[]" stands for every item of an array: "particles.blocks[].min"
    KeyType type;
    std::string unit;       // SI unit, "" for none
    nlohmann::json def;     // the default; null when there is none (required, or see default_note)
    std::string default_note;   // a default that is not a constant ("spacing / 2"), or why there is none
    double lo = 0.0, hi = 0.0;  // bounds of a number, an integer, each element of a vec3 or int_pair
    std::vector<std::string> choices;   // a string's allowed values
    bool required = false;
    std::string variant;    // items of an array that come in kinds ("sphere", "box"): the kind this key belongs to
    std::string meaning;
};

// Every key, parents before their children, in the order docs/SCENES.md lists them.
const std::vector<Key>& keys();
// The key at `path` ("sph.cfl", "obstacles[].radius"); nullptr if none.
const Key* find_key(std::string_view path);

// A rule between keys that the parser checks and JSON Schema cannot say (listed in docs/SCENES.md).
struct Rule {
    std::string keys;   // the keys it involves, as the error message names them
    std::string text;
};
const std::vector<Rule>& rules();

// The generated files: docs/SCENES.md and media/scenes/scene.schema.json (JSON Schema draft 2020-12).
std::string markdown();
std::string json_schema();

}  // namespace ranryu::scene
