"""Minimal reader of deal.II ParameterHandler files for the test scripts:
`set` entries by (subsection, name), with defaults for what a file leaves
out."""


def read_prm(path, defaults=None):
    """Return get(section, key[, default]) over the file's `set` entries."""
    values, section = dict(defaults or {}), []
    for raw in open(path):
        line = raw.split("#")[0].strip()
        if line.startswith("subsection"):
            section.append(line.split(None, 1)[1].strip())
        elif line == "end":
            section.pop()
        elif line.startswith("set"):
            key, value = line[3:].split("=", 1)
            values[(section[-1] if section else "", key.strip())] = value.strip()

    def get(section_name, key, *default):
        if default:
            return values.get((section_name, key), default[0])
        return values[(section_name, key)]

    return get
