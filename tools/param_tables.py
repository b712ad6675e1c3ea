#!/usr/bin/env python3
"""The parameter tables of docs/PARAMETERS.md, generated from the comment tables that stand
beside each Create in src/ (docs/ARCHITECTURE.md, "Checklists"), and checked against the code.

A comment table is a comment line ending in "Parameters:" whose first quoted word is the type
(`// Integrator "path" (integrator_list.inc). Parameters:`), then rows
`//   NAMES  TYPE  DEFAULT  DESCRIPTION`, columns separated by two or more spaces, a row's
continuation lines indented under its description. NAMES is one name or several
(`from, to`), each optionally with aliases in parentheses (`index (eta)`, `Kd (v4: reflectance)`).

  tools/param_tables.py --write   regenerate docs/PARAMETERS.md
  tools/param_tables.py --check   exit 1 if docs/PARAMETERS.md is not what --write writes, or if
                                  a table names a parameter its source file never reads as a
                                  string literal, or the Create below a table reads a literal
                                  parameter name the table does not list
"""
import pathlib
import re
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
DOC = ROOT / "docs" / "PARAMETERS.md"
# A table's header: a comment line ending in "Parameters:" (TAIL), with the directive and its
# quoted names (HEAD_NAME) on that line or on an earlier line of the same comment.
HEAD_NAME = re.compile(r'^\s*//\s*([A-Z]\w*)\s+("[^"]+"(?:,\s*"[^"]+")*)')
# A head's list of names may go on over the next lines: `//   "zsobol", "paddedsobol" ...`.
HEAD_MORE = re.compile(r'^\s*//\s*("[^"]+"(?:,\s*"[^"]+")*)')
TAIL = re.compile(r'^\s*//.*Parameters(?: \([^)]*\))?:\s*$')
ROW = re.compile(r'^\s*//   (\S.*?)\s{2,}(\S.*)$')
CONT = re.compile(r'^\s*//\s{4,}(\S.*)$')
# A parameter read in a Create: p.Float("name", ...), in.params.Int("name"), ps.GetString(...
READ = re.compile(r'\.(?:Get)?(?:Float|Int|Bool|String|Spectrum|SpectrumTex|FloatTex|Tex|'
                  r'Point|Point3|Vector|Normal|PositiveFloat|OptionalImage|Loc|Has)\(\s*"(\w[\w.]*)"')


def names_of(cell):
    """["index", "eta"] of "index (eta)"; ["Kd", "reflectance"] of "Kd (v4: reflectance)"."""
    out = []
    for part in re.split(r',\s*', re.sub(r'\(([^)]*)\)', lambda m: ',' + m.group(1), cell)):
        part = part.strip()
        part = re.sub(r'^v\d:\s*', '', part)
        if re.fullmatch(r'\w[\w.]*', part):  # pbrt-v4's names may be dotted: conductor.eta
            out.append(part)
    return out


def split_row(rest):
    """TYPE, DEFAULT, DESCRIPTION of a row's text after the names (columns: 2+ spaces)."""
    cols = re.split(r'\s{2,}', rest.strip(), maxsplit=2)
    while len(cols) < 3:
        cols.append('')
    return cols


def tables():
    found = []
    for path in sorted((ROOT / "src").rglob("*.cpp")):
        text = path.read_text()
        lines = text.split('\n')
        i = 0
        while i < len(lines):
            m = None
            if TAIL.match(lines[i]):
                j = i
                while j >= 0 and lines[j].lstrip().startswith('//') and not m:
                    m = HEAD_NAME.match(lines[j])
                    j -= 1
            if not m:
                i += 1
                continue
            # One table may serve several types: `// PixelFilter "box", "gaussian" ...`.
            names = re.findall(r'"([^"]+)"', m.group(2))
            k = j + 2
            while k <= i and (more := HEAD_MORE.match(lines[k])):
                names += re.findall(r'"([^"]+)"', more.group(1))
                k += 1
            name = '", "'.join(names)
            table = {"kind": m.group(1), "name": name, "file": path.relative_to(ROOT),
                     "line": i + 1, "rows": []}
            i += 1
            while i < len(lines):
                c = CONT.match(lines[i])
                r = ROW.match(lines[i])
                if table["rows"] and c and not r:
                    table["rows"][-1]["desc"] += ' ' + c.group(1)
                elif r:
                    typ, default, desc = split_row(r.group(2))
                    table["rows"].append({"cell": r.group(1), "names": names_of(r.group(1)),
                                          "type": typ, "default": default, "desc": desc})
                else:
                    break
                i += 1
            if table["rows"]:
                table["text"] = text
                table["body"] = create_body(lines, i)
                found.append(table)
    return found


def create_body(lines, start):
    """The lines of the function that follows a table: to its closing brace, at the indentation
    of the function's first line (column 0, or a member function's)."""
    body = []
    indent = ''
    if start < len(lines):
        indent = lines[start][:len(lines[start]) - len(lines[start].lstrip())]
    for line in lines[start:]:
        body.append(line)
        if line.startswith(indent + '}'):
            break
    return '\n'.join(body)


# WithTexCoordParams(t, primary, fallback, "NAME") reads "NAMEtransform" and "NAMEtexcoord".
TEXCOORD = re.compile(r'WithTexCoordParams\([^;]*?"(\w+)"\)')


# ReadUVRoughness(p, def[, "PREFIX"]) (render/materials.h) reads "PREFIXroughness",
# "PREFIXuroughness", "PREFIXvroughness" and "remaproughness".
ROUGHNESS = re.compile(r'ReadUVRoughness\([^;"]*?(?:"([\w.]*)")?\)')


# ReadSphereMap(p, light) (render/light.h) reads "mapname" and "filename".
SPHERE_MAP = re.compile(r'ReadSphereMap\(')


def literals(text):
    """The quoted parameter names a source text can read: its literals and the names
    WithTexCoordParams, ReadUVRoughness and ReadSphereMap build."""
    built = ''.join(f'"{n}transform" "{n}texcoord"' for n in TEXCOORD.findall(text))
    built += '"mapname" "filename"' * len(SPHERE_MAP.findall(text))
    built += ''.join(f'"{n}roughness" "{n}uroughness" "{n}vroughness" "remaproughness"'
                     for n in ROUGHNESS.findall(text))
    return text + built


# Parameters every directive of a kind shares are read once, by the scene assembly: a table's
# name may be read there instead of in its own file.
SHARED = {
    "Integrator": ["src/assembly/sampler_integrator.cpp",  # maxdepth
                   "src/render/path_integrator.cpp"],   # path's reader, volpath's too
    "LightSource": ["src/assembly/build_context.h"],    # scale (LightParams::Scale)
    "AreaLightSource": ["src/assembly/build_context.h"],  # scale (ScaleParam)
    "Camera": ["src/assembly/camera_film.cpp"],
    "Texture": ["src/assembly/textures.cpp"],          # the 2-D mapping
    "Shape": ["src/geometry/shape_params.cpp"],        # phimax (ShapeParams::PhiMax)
}


# The registries (src/render/*_list.inc) whose every entry needs a table, and the entries that
# need none, with why.
REGISTRIES = ["src/render/integrator_list.inc", "src/render/light_list.inc",
              "src/render/material_list.inc", "src/render/texture_list.inc"]
UNTABLED = {
    "CreateGltfMaterial": "made by the glTF reader from a file's materials, not written in pbrt "
                          "files; its parameters are in the comment above it",
    "CreateInterfaceMaterial": "no parameters",
    "CreateWindyTexture": "no parameters (pbrt-v3's windy waves)",
    "CreatePtexStandIn": "not supported: a constant 0.5 after a warning",
}
ENTRY = re.compile(r'^PRISM_\w+\("([^"]*)",\s*(\w+)\)', re.M)
SHAPE_ENTRY = re.compile(r'^PRISM_SHAPE\((\w+),\s*"([^"]*)"\)', re.M)
CREATE = re.compile(r'\b(Create\w+(?:<\w+>)?)\(')


def problems(found):
    out = []
    tabled = set()
    for t in found:
        m = CREATE.search(t["body"].split('{')[0])
        if m:
            tabled.add(m.group(1))
    for reg in REGISTRIES:
        for name, fn in ENTRY.findall((ROOT / reg).read_text()):
            if fn not in tabled and fn not in UNTABLED:
                out.append(f'{reg}: "{name}" ({fn}) has no parameter table beside its Create')
    for cls, name in SHAPE_ENTRY.findall((ROOT / "src/geometry/shape_list.inc").read_text()):
        if f"CreateShape<{cls}>" not in tabled:
            out.append(f'src/geometry/shape_list.inc: "{name}" (CreateShape<{cls}>) has no '
                       'parameter table beside its Create')
    for t in found:
        text = literals(t["text"])
        shared = literals(''.join((ROOT / f).read_text() for f in SHARED.get(t["kind"], [])))
        listed = {n for r in t["rows"] for n in r["names"]}
        for r in t["rows"]:
            for n in r["names"]:
                if '"' + n + '"' not in text and '"' + n + '"' not in shared:
                    out.append(f'{t["file"]}:{t["line"]}: {t["kind"]} "{t["name"]}" lists '
                               f'"{n}", which neither {t["file"].name} nor the assembly reads')
        for n in sorted(set(READ.findall(t["body"]))):
            if n not in listed:
                out.append(f'{t["file"]}:{t["line"]}: {t["kind"]} "{t["name"]}": its Create '
                           f'reads "{n}", which the table does not list')
    return out


def markdown(found):
    out = ["# Parameters", "",
           "Every parameter of every integrator, light, camera, film, sampler, pixel filter, medium,",
           "material, texture and shape, from the table beside the code that reads it in",
           "src/, generated from those tables by",
           "`tools/param_tables.py --write` (the test `Docs.ParameterTablesMatchTheCode` runs",
           "`--check`: this page, the tables and the names the code reads cannot drift apart).",
           "pbrt-v3's parameter types apply (`spectrum` takes `rgb`, `spectrum` or `blackbody`;",
           "`texture` means a value or a named texture). Directives not listed here are described",
           "in docs/USAGE.md (\"pbrt-v3 support\") and docs/FORMAT.md. `Shape \"(every shape)\"` and",
           "`Material \"(every material)\"` are the parameters every shape and every material takes.",
           ""]
    kinds = {}
    for t in found:
        kinds.setdefault(t["kind"], []).append(t)
    for kind in sorted(kinds):
        out += ["## " + kind, ""]
        for t in sorted(kinds[kind], key=lambda t: t["name"]):
            out += [f'### {kind} "{t["name"]}"', "", f'`{t["file"]}`', "",
                    "| parameter | type | default | meaning |", "|---|---|---|---|"]
            for r in t["rows"]:
                cells = [r["cell"], r["type"], r["default"], r["desc"]]
                out.append("| " + " | ".join(c.replace('|', '\\|') for c in cells) + " |")
            out.append("")
    return '\n'.join(out).rstrip('\n') + '\n'


def main():
    if len(sys.argv) != 2 or sys.argv[1] not in ("--write", "--check"):
        sys.exit(__doc__)
    found = tables()
    text = markdown(found)
    bad = problems(found)
    if sys.argv[1] == "--write":
        DOC.write_text(text)
        print(f"wrote {DOC.relative_to(ROOT)}: {len(found)} tables, "
              f"{sum(len(t['rows']) for t in found)} rows")
    elif not DOC.exists() or DOC.read_text() != text:
        bad.append(f"{DOC.relative_to(ROOT)} is not generated from the tables: run "
                   "tools/param_tables.py --write")
    for b in bad:
        print(b, file=sys.stderr)
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
