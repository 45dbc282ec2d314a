// A minimal streaming JSON writer with deterministic formatting (C locale, shortest round-trip
// numbers, keys in the order written). Output is one object per line unless pretty is set.
#pragma once

#include <charconv>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace limn {

class JsonWriter {
public:
    explicit JsonWriter(bool pretty = false) : pretty_(pretty) {}

    JsonWriter& beginObject() { return open('{'); }
    JsonWriter& endObject() { return close('}'); }
    JsonWriter& beginArray() { return open('['); }
    JsonWriter& endArray() { return close(']'); }

    JsonWriter& key(const std::string& k) {
        separator();
        quote(k);
        out_ += pretty_ ? ": " : ":";
        afterKey_ = true;
        return *this;
    }
    JsonWriter& value(const std::string& s) {
        separator();
        quote(s);
        return *this;
    }
    JsonWriter& value(const char* s) { return value(std::string(s)); }
    JsonWriter& value(bool b) {
        separator();
        out_ += b ? "true" : "false";
        return *this;
    }
    JsonWriter& value(double d) {
        separator();
        if (!std::isfinite(d)) {
            out_ += "null";
            return *this;
        }
        char buf[32];
        auto [p, ec] = std::to_chars(buf, buf + sizeof buf, d);
        (void)ec;
        out_.append(buf, p);
        return *this;
    }
    template <class I>
        requires std::is_integral_v<I> && (!std::is_same_v<I, bool>)
    JsonWriter& value(I i) {
        separator();
        out_ += std::to_string(i);
        return *this;
    }
    template <class T>
    JsonWriter& field(const std::string& k, const T& v) {
        key(k);
        return value(v);
    }

    const std::string& str() const { return out_; }

private:
    JsonWriter& open(char c) {
        separator();
        out_ += c;
        first_.push_back(true);
        return *this;
    }
    JsonWriter& close(char c) {
        bool empty = first_.back();
        first_.pop_back();
        if (pretty_ && !empty) newline();
        out_ += c;
        return *this;
    }
    void separator() {
        if (afterKey_) {
            afterKey_ = false;
            return;
        }
        if (first_.empty()) return;
        if (!first_.back()) out_ += ',';
        first_.back() = false;
        if (pretty_) newline();
    }
    void newline() {
        out_ += '\n';
        out_.append(first_.size() * 2, ' ');
    }
    void quote(const std::string& s) {
        out_ += '"';
        for (unsigned char c : s) {
            switch (c) {
            case '"': out_ += "\\\""; break;
            case '\\': out_ += "\\\\"; break;
            case '\n': out_ += "\\n"; break;
            case '\r': out_ += "\\r"; break;
            case '\t': out_ += "\\t"; break;
            default:
                if (c < 0x20) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\u%04x", c);
                    out_ += buf;
                } else {
                    out_ += static_cast<char>(c);
                }
            }
        }
        out_ += '"';
    }

    bool pretty_;
    bool afterKey_ = false;
    std::vector<bool> first_;
    std::string out_;
};

} // namespace limn
