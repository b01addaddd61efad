#pragma once
// Settings: the struct and its declaration table are both generated from settings.def (declare once).
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

namespace deepgi {

// The choices of the DEEPGI_ENUM settings, in the order of their choice strings in settings.def.
enum class GBufferGeneration { Predicted, DepthPeel };
enum class LayerRouting { Auto, Vertex, Geometry };
enum class Layer2Prepass { Auto, On, Off };
enum class FilterOrder { BlurFirst, TemporalFirst };
enum class RadiosityResolution { Auto, Full, Half, Quarter, Eighth };
enum class RadiosityInterleave { Auto, Off, Two, Four };
enum class CompositeMode { Physical, Seed };
enum class Tonemap { Clamp, Aces };

// One struct per DEEPGI_GROUP (Filament's Options.h): a pass reads only its stage's group,
// `const BlurSettings& blur = settings;`.
struct SettingsPrologue {  // empty: settings.def opens with a group
#define DEEPGI_GROUP(Type) }; struct Type {
#define DEEPGI_SETTING(member, key, type, def, lo, hi, unit, group, effect) type member = def;
#define DEEPGI_ENUM(member, key, EnumType, def, choices, group, effect) EnumType member = def;
#include "renderer/core/settings.def"
#undef DEEPGI_GROUP
#undef DEEPGI_SETTING
#undef DEEPGI_ENUM
};

// Every setting, flat (s.radius) through its groups.
struct Settings : SettingsPrologue
#define DEEPGI_GROUP(Type) , Type
#define DEEPGI_SETTING(...)
#define DEEPGI_ENUM(...)
#include "renderer/core/settings.def"
#undef DEEPGI_GROUP
#undef DEEPGI_SETTING
#undef DEEPGI_ENUM
{
    bool operator==(const Settings& o) const;
    bool operator!=(const Settings& o) const { return !(*this == o); }
};

enum class SettingType { Float, Int, Bool, Enum };

struct SettingInfo {
    const char* key;
    SettingType type;
    double def, min, max;
    const char* unit;
    const char* group;
    const char* effect;
    std::vector<std::string> choices;  // Enum only
    // Access to the member, as a double (bool 0/1, enum index).
    double (*get)(const Settings&);
    void (*set)(Settings&, double);
};

const std::vector<SettingInfo>& settingTable();
const SettingInfo* findSetting(const std::string& key);
std::vector<std::string> settingGroups();  // in pipeline order

// "key=value"; value is a number, true/false/on/off, or an enum choice name. A value outside the declared range
// (or a fraction for an integer setting) throws std::runtime_error naming the key, the value and the range.
void applySetting(Settings& s, const std::string& key, const std::string& value);
void applyAssignment(Settings& s, const std::string& keyEqualsValue);

nlohmann::json settingsToJson(const Settings& s);
// Unknown keys and wrong types throw std::runtime_error naming the key; `where` names the file for messages.
// Out-of-range values throw too (--settings files and presets).
void applySettingsJson(Settings& s, const nlohmann::json& j, const std::string& where);
// For saved state (the viewer's): an out-of-range value is clamped and an unknown key or wrong type skipped, each
// with a returned warning naming `where`, the key, the value and the range.
std::vector<std::string> applySettingsJsonLeniently(Settings& s, const nlohmann::json& j, const std::string& where);
void loadSettingsFile(Settings& s, const std::string& path);
void saveSettingsFile(const Settings& s, const std::string& path);

// The unit of lengths relative to the scene, as settings.def writes it.
inline constexpr const char* kSceneSizeUnit = "x scene size";
// The scene units per relative length: scene.length_unit, or sceneSize when it is 0.
float lengthUnit(const Settings& s, float sceneSize);
// A copy with every "x scene size" length multiplied out into scene units (what the passes use).
Settings resolveLengths(const Settings& s, float sceneSize);

// Presets "performance", "balanced", "quality" live in assets/presets/<name>.json.
std::vector<std::string> presetNames();
void applyPreset(Settings& s, const std::string& name);
std::string formatSettingValue(const SettingInfo& info, double v);

}  // namespace deepgi
