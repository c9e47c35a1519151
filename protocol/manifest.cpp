#include "protocol/manifest.hpp"

namespace arena::protocol {

namespace {

bool is_key(std::string_view s) {
    if (s.empty() || s.size() > 32) return false;
    for (const char c : s)
        if (!((c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_')) return false;
    return true;
}

std::string text_problem(const std::string& where, const std::string& text) {
    if (text.size() > max_manifest_text) return where + ": longer than " + std::to_string(max_manifest_text) + " bytes";
    return "";
}

std::string fields_problem(const char* list, const std::vector<game_field>& fields) {
    if (fields.size() > max_game_fields)
        return std::string(list) + ": more than " + std::to_string(max_game_fields) + " fields";
    for (size_t i = 0; i < fields.size(); ++i) {
        const std::string where = std::string(list) + "[" + std::to_string(i) + "]";
        if (!is_key(fields[i].name)) return where + ".name: 1 to 32 of a-z, 0-9 and _";
        if (std::string p = text_problem(where + ".label", fields[i].label); !p.empty()) return p;
        for (size_t k = 0; k < i; ++k)
            if (fields[k].name == fields[i].name) return where + ".name: '" + fields[i].name + "' twice";
    }
    return "";
}

std::string str(const flatbuffers::String* s) {
    return s ? s->str() : std::string();
}

template <class T>
flatbuffers::Offset<flatbuffers::Vector<flatbuffers::Offset<T>>> tables(flatbuffers::FlatBufferBuilder& fbb,
                                                                        std::vector<flatbuffers::Offset<T>>& offsets) {
    return offsets.empty() ? 0 : fbb.CreateVector(offsets);
}

flatbuffers::Offset<flatbuffers::Vector<flatbuffers::Offset<GameField>>> create_fields(
    flatbuffers::FlatBufferBuilder& fbb, const std::vector<game_field>& fields) {
    std::vector<flatbuffers::Offset<GameField>> out;
    for (const game_field& f : fields)
        out.push_back(CreateGameField(fbb, fbb.CreateString(f.name), fbb.CreateString(f.label), f.kind));
    return tables(fbb, out);
}

std::vector<game_field> read_fields(const flatbuffers::Vector<flatbuffers::Offset<GameField>>* fields) {
    std::vector<game_field> out;
    if (fields)
        for (const GameField* f : *fields) out.push_back({str(f->name()), str(f->label()), f->kind()});
    return out;
}

}  // namespace

int game_manifest::player_field(std::string_view field) const {
    for (size_t i = 0; i < player_fields.size(); ++i)
        if (player_fields[i].name == field) return static_cast<int>(i);
    return -1;
}

std::string manifest_problem(const game_manifest& m) {
    if (m.empty()) return "";
    if (!is_key(m.name)) return "name: 1 to 32 of a-z, 0-9 and _";
    if (std::string p = fields_problem("player_fields", m.player_fields); !p.empty()) return p;
    if (std::string p = fields_problem("team_fields", m.team_fields); !p.empty()) return p;
    if (m.teams.size() > max_game_teams) return "teams: more than " + std::to_string(max_game_teams);
    for (size_t i = 0; i < m.teams.size(); ++i) {
        const std::string where = "teams[" + std::to_string(i) + "]";
        if (std::string p = text_problem(where + ".name", m.teams[i].name); !p.empty()) return p;
        if (std::string p = text_problem(where + ".colour", m.teams[i].colour); !p.empty()) return p;
    }
    if (!m.rank_field.empty() && m.player_field(m.rank_field) < 0)
        return "rank_field: '" + m.rank_field + "' is not a player field";
    if (m.events.size() > max_game_events) return "events: more than " + std::to_string(max_game_events);
    for (size_t i = 0; i < m.events.size(); ++i) {
        const std::string where = "events[" + std::to_string(i) + "]";
        if (!is_key(m.events[i].name)) return where + ".name: 1 to 32 of a-z, 0-9 and _";
        if (m.events[i].values.size() > max_event_values)
            return where + ".values: more than " + std::to_string(max_event_values);
        for (const std::string& v : m.events[i].values)
            if (!is_key(v)) return where + ".values: '" + v.substr(0, 40) + "' is not a name";
        if (std::string p = text_problem(where + ".message", m.events[i].message); !p.empty()) return p;
    }
    if (m.body_tags.size() > max_body_tags) return "body_tags: more than " + std::to_string(max_body_tags);
    for (size_t i = 0; i < m.body_tags.size(); ++i) {
        const std::string where = "body_tags[" + std::to_string(i) + "]";
        for (const std::string* t : {&m.body_tags[i].name, &m.body_tags[i].style, &m.body_tags[i].colour})
            if (std::string p = text_problem(where, *t); !p.empty()) return p;
    }
    if (m.inputs.size() > max_game_inputs) return "inputs: more than " + std::to_string(max_game_inputs);
    for (size_t i = 0; i < m.inputs.size(); ++i) {
        const std::string where = "inputs[" + std::to_string(i) + "]";
        if (m.inputs[i].button > 7) return where + ".button: a bit from 0 to 7";
        if (std::string p = text_problem(where + ".name", m.inputs[i].name); !p.empty()) return p;
        if (std::string p = text_problem(where + ".key", m.inputs[i].key); !p.empty()) return p;
    }
    return "";
}

std::vector<std::uint8_t> encode_manifest(const game_manifest& m) {
    if (m.empty()) return {};
    flatbuffers::FlatBufferBuilder fbb(1024);
    const auto player_fields = create_fields(fbb, m.player_fields);
    const auto team_fields = create_fields(fbb, m.team_fields);
    std::vector<flatbuffers::Offset<GameTeam>> teams;
    for (const game_team& t : m.teams)
        teams.push_back(CreateGameTeam(fbb, fbb.CreateString(t.name), fbb.CreateString(t.colour)));
    std::vector<flatbuffers::Offset<GameEventSpec>> events;
    for (const event_spec& e : m.events) {
        std::vector<flatbuffers::Offset<flatbuffers::String>> values;
        for (const std::string& v : e.values) values.push_back(fbb.CreateString(v));
        events.push_back(
            CreateGameEventSpec(fbb, fbb.CreateString(e.name), fbb.CreateVector(values), fbb.CreateString(e.message)));
    }
    std::vector<flatbuffers::Offset<BodyTag>> tags;
    for (const body_tag& t : m.body_tags)
        tags.push_back(CreateBodyTag(fbb, t.kind, fbb.CreateString(t.name), fbb.CreateString(t.style),
                                     fbb.CreateString(t.colour)));
    std::vector<flatbuffers::Offset<GameInput>> inputs;
    for (const game_input& in : m.inputs)
        inputs.push_back(CreateGameInput(fbb, fbb.CreateString(in.name), in.button, fbb.CreateString(in.key)));
    const auto name = fbb.CreateString(m.name);
    const auto rank = fbb.CreateString(m.rank_field);
    const auto team_list = tables(fbb, teams);
    const auto event_list = tables(fbb, events);
    const auto tag_list = tables(fbb, tags);
    const auto input_list = tables(fbb, inputs);
    fbb.Finish(CreateGameManifest(fbb, name, player_fields, team_fields, team_list, rank, m.rank_ascending, event_list,
                                  tag_list, input_list));
    return {fbb.GetBufferPointer(), fbb.GetBufferPointer() + fbb.GetSize()};
}

result<game_manifest> decode_manifest(std::span<const std::uint8_t> buffer) {
    using out = result<game_manifest>;
    game_manifest m;
    if (buffer.empty()) return out::success(m);
    flatbuffers::Verifier::Options options;
    options.max_depth = 4;  // GameManifest -> a list's table (vectors and strings do not count)
    options.max_tables = max_manifest_tables;
    flatbuffers::Verifier verifier(buffer.data(), buffer.size(), options);
    if (!verifier.VerifyBuffer<GameManifest>(nullptr)) return out::failure("FlatBuffer verification failed");
    const GameManifest* t = flatbuffers::GetRoot<GameManifest>(buffer.data());
    m.name = str(t->name());
    m.player_fields = read_fields(t->player_fields());
    m.team_fields = read_fields(t->team_fields());
    if (t->teams())
        for (const GameTeam* team : *t->teams()) m.teams.push_back({str(team->name()), str(team->colour())});
    m.rank_field = str(t->rank_field());
    m.rank_ascending = t->rank_ascending();
    if (t->events())
        for (const GameEventSpec* e : *t->events()) {
            event_spec spec{str(e->name()), {}, str(e->message())};
            if (e->values())
                for (const flatbuffers::String* v : *e->values()) spec.values.push_back(str(v));
            m.events.push_back(std::move(spec));
        }
    if (t->body_tags())
        for (const BodyTag* b : *t->body_tags())
            m.body_tags.push_back({b->kind(), str(b->name()), str(b->style()), str(b->colour())});
    if (t->inputs())
        for (const GameInput* in : *t->inputs()) m.inputs.push_back({str(in->name()), in->button(), str(in->key())});
    if (std::string bad = manifest_problem(m); !bad.empty()) return out::failure(std::move(bad));
    return out::success(std::move(m));
}

GameValue to_wire(const game_value& v) {
    return {v.owner, v.field, v.value};
}

game_value from_wire(const GameValue& v) {
    return {v.owner(), v.field(), v.value()};
}

GameEventRecord to_wire(const event_record& e) {
    return {e.sequence, e.tick, e.kind, e.values[0], e.values[1], e.values[2], e.values[3]};
}

event_record from_wire(const GameEventRecord& e) {
    return {e.sequence(), e.tick(), e.kind(), {e.v0(), e.v1(), e.v2(), e.v3()}};
}

}  // namespace arena::protocol
