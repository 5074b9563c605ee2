"""The plugin's generated proxy XML files (build tree, Plugin/*.xml, with the shared fragments of
Plugin/Fragments inlined) against the VTK classes they describe:

* every one-element Int/Double/IdType vector property with command="SetX" has a default_values
  equal to GetX() of a fresh object of the proxy's class (the C++ defaults are the truth), and
  that default lies inside the property's range, enumeration or boolean domain;
* a property that several proxies define has the same label, command, type and domains in all
  of them, unless the proxy is listed in OWN_DOMAINS with the reason;
* every proxy of EXPECTED_PROXIES (the public names of interface.md) is defined, with its class,
  its label and the menu category "Optimal Transport".

Arguments: the generated XML files, or directories holding them."""

import glob
import math
import os
import sys
import xml.etree.ElementTree as ET

import otparam

# (proxy name, property name) -> why that proxy's property has domains of its own. Every other
# proxy defining the property must agree with the others; keep this list small.
OWN_DOMAINS = {
    ("ConformalDiskMap", "Tolerance"):
        "the conformal map's step of the boundary angles (radians, default 1e-6), not the "
        "transport's relative cell-mass error (default 1e-10)",
    ("ConformalDiskMap", "MaximumNumberOfIterations"):
        "boundary-angle iterations, of which 0 (boundary-first flattening only) is valid; the "
        "transport needs at least one Newton iteration",
    ("AreaPreservingParameterization", "NumberOfSamples"):
        "0 (the default) means automatic there: the count follows the surface's point count; "
        "the sampler itself needs an explicit count of at least 3",
}

# Proxy name -> (class, label), as interface.md fixes them.
EXPECTED_PROXIES = {
    "ConformalDiskMap": ("vtkConformalDiskMap", "Conformal Disk Map"),
    "AdaptiveDensitySampler": ("vtkAdaptiveDensitySampler", "Adaptive Density Sampler"),
    "SemiDiscreteOTSolver": ("vtkSemiDiscreteOTSolver", "Semi-Discrete OT Solver"),
    "AreaPreservingParameterization": ("vtkAreaPreservingParam",
                                       "Area-Preserving Parameterization"),
    "SphericalOTSolver": ("vtkSphericalOTSolver", "Spherical OT Solver"),
    "ConformalSphereMap": ("vtkConformalSphereMap", "Conformal Sphere Map"),
}

NUMERIC = {"IntVectorProperty": int, "IdTypeVectorProperty": int, "DoubleVectorProperty": float}

problems = []


def problem(message):
    problems.append(message)
    print("MISMATCH:", message, flush=True)


def xml_files(arguments):
    files = []
    for argument in arguments:
        if os.path.isdir(argument):
            files.extend(sorted(glob.glob(os.path.join(argument, "*.xml"))))
        else:
            files.append(argument)
    return files


def domains(prop, convert):
    """The property's domains, comparable across proxies: (tag, min, max) of a range domain,
    (tag, entries) of an enumeration, (tag,) of any other."""
    result = []
    for child in prop:
        if child.tag.endswith("RangeDomain"):
            bounds = tuple(None if child.get(key) is None else convert(child.get(key))
                           for key in ("min", "max"))
            result.append((child.tag,) + bounds)
        elif child.tag == "EnumerationDomain":
            entries = tuple((int(entry.get("value")), entry.get("text"))
                            for entry in child.findall("Entry"))
            result.append((child.tag, entries))
        elif child.tag.endswith("Domain"):
            result.append((child.tag,))
    return tuple(result)


def same_value(kind, xml_value, cxx_value):
    if kind is float:
        return math.isclose(xml_value, float(cxx_value), rel_tol=1e-12, abs_tol=0.0)
    return xml_value == int(cxx_value)


def check_default(where, prop, kind, value):
    """The default lies inside each domain of the property."""
    for child in prop:
        if child.tag.endswith("RangeDomain"):
            low, high = child.get("min"), child.get("max")
            if (low is not None and value < kind(low)) or (high is not None and value > kind(high)):
                problem(f"{where}: default {value} outside the range [{low}, {high}]")
        elif child.tag == "EnumerationDomain":
            values = [int(entry.get("value")) for entry in child.findall("Entry")]
            if value not in values:
                problem(f"{where}: default {value} is none of the enumeration values {values}")
        elif child.tag == "BooleanDomain" and value not in (0, 1):
            problem(f"{where}: default {value} of a boolean property is neither 0 nor 1")


files = xml_files(sys.argv[1:])
if not files:
    problem(f"no proxy XML files given (arguments: {sys.argv[1:]})")

checked = 0
proxies = 0
# property name -> [(proxy name, file, (tag, label, command), domains)]
shared = {}
# proxy name -> (class, label, menu category)
found = {}
for path in files:
    with open(path, encoding="utf-8") as stream:
        text = stream.read()
    if "@OTPARAM_" in text:
        problem(f"{path}: a fragment reference was left unsubstituted")
    try:
        root = ET.fromstring(text)
    except ET.ParseError as error:
        problem(f"{path} is not well-formed XML: {error}")
        continue
    for proxy in root.iter("SourceProxy"):
        proxies += 1
        name, cls = proxy.get("name"), proxy.get("class")
        menu = proxy.find("Hints/ShowInMenu")
        found[name] = (cls, proxy.get("label"), menu.get("category") if menu is not None else None)
        factory = getattr(otparam, cls or "", None)
        if factory is None:
            problem(f"{path}: proxy {name}: class {cls!r} is not in the otparam package")
            continue
        instance = factory()
        for prop in proxy:
            kind = NUMERIC.get(prop.tag)
            if kind is None or prop.get("information_only") == "1":
                continue
            prop_name, command = prop.get("name"), prop.get("command") or ""
            where = f"{name}.{prop_name}"
            shared.setdefault(prop_name, []).append(
                (name, path, (prop.tag, prop.get("label"), command), domains(prop, kind)))
            if prop.get("number_of_elements") != "1" or not command.startswith("Set"):
                continue
            getter = getattr(instance, "Get" + command[3:], None)
            if getter is None:
                problem(f"{where}: {cls} has no Get{command[3:]} to compare the default with")
                continue
            checked += 1
            default = prop.get("default_values")
            if default is None:
                problem(f"{where}: no default_values ({cls}.Get{command[3:]}() = {getter()})")
                continue
            try:
                value = kind(default)
            except ValueError:
                problem(f"{where}: default_values {default!r} is not a {kind.__name__}")
                continue
            if not same_value(kind, value, getter()):
                problem(f"{where}: XML default_values {default} but "
                        f"{cls}.Get{command[3:]}() = {getter()}")
            check_default(where, prop, kind, value)

for name, (cls, label) in EXPECTED_PROXIES.items():
    if name not in found:
        problem(f"no proxy {name} ({label}, {cls}) in the generated XML files")
    elif found[name] != (cls, label, "Optimal Transport"):
        problem(f"proxy {name}: (class, label, menu category) {found[name]} but "
                f"{(cls, label, 'Optimal Transport')} expected")

# One vocabulary: a property name means the same thing (label, command, domains) everywhere.
for key, reason in OWN_DOMAINS.items():
    if not any(entry[0] == key[0] for entry in shared.get(key[1], [])):
        problem(f"OWN_DOMAINS lists {key[0]}.{key[1]}, which no XML defines")
for prop_name, entries in sorted(shared.items()):
    compared = [entry for entry in entries if (entry[0], prop_name) not in OWN_DOMAINS]
    exempt = [entry for entry in entries if (entry[0], prop_name) in OWN_DOMAINS]
    for other in compared[1:]:
        first = compared[0]
        if other[2] != first[2]:
            problem(f"{prop_name}: (element, label, command) {other[2]} in {other[0]} but "
                    f"{first[2]} in {first[0]}")
        if other[3] != first[3]:
            problem(f"{prop_name}: domains {other[3]} in {other[0]} but {first[3]} in "
                    f"{first[0]} (share them through Plugin/Fragments, or list the proxy in "
                    "OWN_DOMAINS with the reason)")
    for entry in exempt:
        if compared and entry[3] == compared[0][3]:
            problem(f"{entry[0]}.{prop_name}: listed in OWN_DOMAINS but its domains are those "
                    f"of {compared[0][0]}; drop it from the list")
    if len(entries) > 1:
        print(f"{prop_name}: in {', '.join(entry[0] for entry in entries)}"
              + (f" ({', '.join(entry[0] for entry in exempt)} with domains of its own)"
                 if exempt else ""))

print(f"{checked} properties checked against the classes' defaults in {proxies} proxies of "
      f"{len(files)} files; {len(problems)} mismatch(es)", flush=True)
if checked == 0:
    print("FAIL: no property was checked", flush=True)
    sys.exit(1)
if problems:
    sys.exit(1)
print("all checks passed", flush=True)
