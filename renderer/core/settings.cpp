#include "renderer/core/settings.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace deepgi {

bool Settings::operator==(const Settings& o) const {
#define DEEPGI_GROUP(Type)
#define DEEPGI_SETTING(member, ...) if (member != o.member) return false;
#define DEEPGI_ENUM(member, ...) if (member != o.member) return false;
#include "renderer/core/settings.def"
#undef DEEPGI_GROUP
#undef DEEPGI_SETTING
#undef DEEPGI_ENUM
    return true;
}

namespace {
std::vector<std::string> splitChoices(const char* s) {
    std::vector<std::string> out;
    std::stringstream ss(s);
    std::string item;
    while (std::getline(ss, item, '|')) out.push_back(item);
    return out;
}
template <class T> SettingType typeOf();
template <> SettingType typeOf<float>() { return SettingType::Float; }
template <> SettingType typeOf<int>() { return SettingType::Int; }
template <> SettingType typeOf<bool>() { return SettingType::Bool; }

// Thrown for a value outside the declared range; the viewer's state file turns it into a warning and a clamp.
struct OutOfRange : std::runtime_error {
    using std::runtime_error::runtime_error;
};

std::string rangeText(const SettingInfo& info) {
    std::string r = "[" + formatSettingValue(info, info.min) + ", " + formatSettingValue(info, info.max) + "]";
    if (info.unit && *info.unit) r += std::string(" ") + info.unit;
    return r;
}

// The value as given, or an error naming key, value and range: never a silent clamp.
double checkedValue(const SettingInfo& info, double v, const std::string& text) {
    if (!std::isfinite(v)) throw std::runtime_error(std::string("setting '") + info.key + "': value is not finite");
    if (info.type == SettingType::Int && v != std::floor(v))
        throw std::runtime_error(std::string("setting '") + info.key + "' expects an integer, got " + text);
    if (v < info.min || v > info.max)
        throw OutOfRange(std::string("setting '") + info.key + "' = " + text + " is out of range " + rangeText(info));
    return v;
}

std::string numberText(double v) {
    std::ostringstream os;
    os << v;
    return os.str();
}

// One "key": value of a settings JSON object. Throws std::runtime_error (OutOfRange for a range problem).
void applyJsonValue(Settings& s, const std::string& key, const nlohmann::json& v) {
    const SettingInfo* info = findSetting(key);
    if (!info) throw std::runtime_error("unknown setting '" + key + "'");
    if (v.is_boolean()) applySetting(s, key, v.get<bool>() ? "true" : "false");
    else if (v.is_number()) {
        if (info->type == SettingType::Bool || info->type == SettingType::Enum)
            throw std::runtime_error("setting '" + key + "' has the wrong type");
        const double d = v.get<double>();
        info->set(s, checkedValue(*info, d, numberText(d)));
    } else if (v.is_string()) applySetting(s, key, v.get<std::string>());
    else throw std::runtime_error("setting '" + key + "' has the wrong type");
}
}  // namespace

const std::vector<SettingInfo>& settingTable() {
    static const std::vector<SettingInfo> table = {
#define DEEPGI_SETTING(member, key, type, def, lo, hi, unit, group, effect)                                    \
    SettingInfo{key, typeOf<type>(), double(def), double(lo), double(hi), unit, group, effect, {},             \
                [](const Settings& s) { return double(s.member); },                                            \
                [](Settings& s, double v) { s.member = std::is_same<type, bool>::value ? type(v != 0.0)        \
                                                     : std::is_same<type, int>::value ? type(std::lround(v)) : type(v); }},
#define DEEPGI_ENUM(member, key, EnumType, def, choices, group, effect)                                        \
    SettingInfo{key, SettingType::Enum, double(int(def)), 0.0, double(splitChoices(choices).size() - 1), "", group, \
                effect, splitChoices(choices), [](const Settings& s) { return double(int(s.member)); },         \
                [](Settings& s, double v) { s.member = EnumType(std::lround(v)); }},
#define DEEPGI_GROUP(Type)
#include "renderer/core/settings.def"
#undef DEEPGI_GROUP
#undef DEEPGI_SETTING
#undef DEEPGI_ENUM
    };
    return table;
}

float lengthUnit(const Settings& s, float sceneSize) {
    if (s.lengthUnit > 0.0f) return s.lengthUnit;
    return std::isfinite(sceneSize) && sceneSize > 0.0f ? sceneSize : 1.0f;
}

Settings resolveLengths(const Settings& s, float sceneSize) {
    const double unit = lengthUnit(s, sceneSize);
    Settings out = s;
    for (const auto& info : settingTable())
        if (std::string(info.unit) == kSceneSizeUnit) info.set(out, info.get(s) * unit);
    return out;
}

const SettingInfo* findSetting(const std::string& key) {
    for (const auto& s : settingTable()) if (key == s.key) return &s;
    return nullptr;
}

std::vector<std::string> settingGroups() {
    std::vector<std::string> groups;
    for (const auto& s : settingTable())
        if (std::find(groups.begin(), groups.end(), s.group) == groups.end()) groups.push_back(s.group);
    return groups;
}

std::string formatSettingValue(const SettingInfo& info, double v) {
    switch (info.type) {
    case SettingType::Bool: return v != 0.0 ? "true" : "false";
    case SettingType::Int: return std::to_string(std::lround(v));
    case SettingType::Enum: {
        long i = std::lround(v);
        return (i >= 0 && i < (long)info.choices.size()) ? info.choices[i] : std::to_string(i);
    }
    case SettingType::Float: {
        std::ostringstream os;
        os << v;
        return os.str();
    }
    }
    return "";
}

void applySetting(Settings& s, const std::string& key, const std::string& value) {
    const SettingInfo* info = findSetting(key);
    if (!info) throw std::runtime_error("unknown setting '" + key + "' (see `deepgi settings`)");
    double v = 0.0;
    if (info->type == SettingType::Bool) {
        if (value == "true" || value == "on" || value == "1") v = 1.0;
        else if (value == "false" || value == "off" || value == "0") v = 0.0;
        else throw std::runtime_error("setting '" + key + "' expects true/false, got '" + value + "'");
    } else if (info->type == SettingType::Enum) {
        auto it = std::find(info->choices.begin(), info->choices.end(), value);
        if (it == info->choices.end()) {
            std::string all;
            for (const auto& c : info->choices) all += (all.empty() ? "" : "|") + c;
            throw std::runtime_error("setting '" + key + "' expects one of " + all + ", got '" + value + "'");
        }
        v = double(it - info->choices.begin());
    } else {
        size_t used = 0;
        try { v = std::stod(value, &used); } catch (...) { used = 0; }
        if (used == 0 || used != value.size())
            throw std::runtime_error("setting '" + key + "' expects a number, got '" + value + "'");
    }
    info->set(s, checkedValue(*info, v, value));
}

void applyAssignment(Settings& s, const std::string& kv) {
    auto eq = kv.find('=');
    if (eq == std::string::npos) throw std::runtime_error("--set expects key=value, got '" + kv + "'");
    applySetting(s, kv.substr(0, eq), kv.substr(eq + 1));
}

nlohmann::json settingsToJson(const Settings& s) {
    nlohmann::json j = nlohmann::json::object();
    for (const auto& info : settingTable()) {
        double v = info.get(s);
        switch (info.type) {
        case SettingType::Bool: j[info.key] = v != 0.0; break;
        case SettingType::Int: j[info.key] = std::lround(v); break;
        case SettingType::Enum: j[info.key] = formatSettingValue(info, v); break;
        case SettingType::Float: j[info.key] = v; break;
        }
    }
    return j;
}

void applySettingsJson(Settings& s, const nlohmann::json& j, const std::string& where) {
    if (!j.is_object()) throw std::runtime_error(where + ": settings must be a JSON object of \"key\": value");
    for (auto it = j.begin(); it != j.end(); ++it) {
        try {
            applyJsonValue(s, it.key(), it.value());
        } catch (const std::runtime_error& e) {
            throw std::runtime_error(where + ": " + e.what());
        }
    }
}

std::vector<std::string> applySettingsJsonLeniently(Settings& s, const nlohmann::json& j, const std::string& where) {
    std::vector<std::string> warnings;
    if (!j.is_object()) return {where + ": settings must be a JSON object of \"key\": value; ignored"};
    for (auto it = j.begin(); it != j.end(); ++it) {
        try {
            applyJsonValue(s, it.key(), it.value());
        } catch (const OutOfRange& e) {
            const SettingInfo* info = findSetting(it.key());
            const double given = it.value().is_number() ? it.value().get<double>()
                                                        : std::stod(it.value().get<std::string>());  // parsed before
            const double clamped = std::min(std::max(given, info->min), info->max);
            info->set(s, clamped);
            warnings.push_back(where + ": " + e.what() + "; using " + formatSettingValue(*info, clamped));
        } catch (const std::exception& e) {
            warnings.push_back(where + ": " + e.what() + "; ignored");
        }
    }
    return warnings;
}

void loadSettingsFile(Settings& s, const std::string& path) {
    std::ifstream f(path);
    if (!f) throw std::runtime_error(path + ": cannot open settings file");
    nlohmann::json j;
    try { j = nlohmann::json::parse(f); } catch (const std::exception& e) {
        throw std::runtime_error(path + ": invalid JSON: " + e.what());
    }
    applySettingsJson(s, j, path);
}

void saveSettingsFile(const Settings& s, const std::string& path) {
    std::ofstream f(path);
    if (!f) throw std::runtime_error(path + ": cannot write settings file");
    f << settingsToJson(s).dump(2) << "\n";
}

std::vector<std::string> presetNames() { return {"performance", "balanced", "quality"}; }

void applyPreset(Settings& s, const std::string& name) {
    auto names = presetNames();
    if (std::find(names.begin(), names.end(), name) == names.end())
        throw std::runtime_error("unknown preset '" + name + "' (performance, balanced, quality)");
    loadSettingsFile(s, std::string(DEEPGI_ASSET_DIR) + "/presets/" + name + ".json");
}

}  // namespace deepgi
