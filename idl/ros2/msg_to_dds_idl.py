#!/usr/bin/env python3
"""The DDS IDL that ROS 2's rosidl_generator_dds_idl makes of a package's .msg files, without ROS.

ROS 2 puts the DDS type of message <pkg>/msg/<Type> in module <pkg>::msg::dds_ as struct <Type>_,
each member named with a trailing underscore, a nested message as <pkg>::msg::dds_::<Nested>_,
`string<=N` as string<N>, `T[<=N]` as sequence<T, N>, `T[]` as sequence<T>, `T[N]` as an array,
and constants in a module <Type>_Constants. fastddsgen compiles the result into types whose names
and wire layout are what a ROS 2 node (rmw_fastrtps) sends and expects; teleop's tests exchange
samples between those types and teleop's own (test/transport/ros2/).

usage: msg_to_dds_idl.py --package teleop_msgs --out DIR FILE.msg...   writes DIR/<Type>_.idl

A message of another package (std_msgs/Header) is included as "std_msgs/msg/Header_.idl": write
each package into <root>/<package>/msg and compile with -I <root>.
"""

import argparse
import pathlib
import re
import sys

# rosidl's primitive types and their IDL (rosidl_generator_dds_idl's mapping)
PRIMITIVES = {
    'bool': 'boolean',
    'byte': 'octet',
    'char': 'char',
    'int8': 'octet',
    'uint8': 'octet',
    'int16': 'short',
    'uint16': 'unsigned short',
    'int32': 'long',
    'uint32': 'unsigned long',
    'int64': 'long long',
    'uint64': 'unsigned long long',
    'float32': 'float',
    'float64': 'double',
    'string': 'string',
    'wstring': 'wstring',
}

# "type name", "type NAME=value"; a type is base, base<=N (strings), with [N], [<=N] or []
FIELD = re.compile(r'^(?P<type>\S+)\s+(?P<name>[A-Za-z][A-Za-z0-9_]*)\s*(?P<rest>.*)$')
TYPE = re.compile(r'^(?P<base>[A-Za-z][A-Za-z0-9_/]*)(<=(?P<strbound>\d+))?(\[(?P<array>(<=)?\d*)\])?$')


class MsgError(Exception):
    pass


def idl_base_type(base, strbound, package, includes):
    if base in PRIMITIVES:
        idl = PRIMITIVES[base]
        if strbound is not None:
            if base not in ('string', 'wstring'):
                raise MsgError(f'only strings have an upper bound, not {base}')
            idl += f'<{strbound}>'
        return idl
    if strbound is not None:
        raise MsgError(f'{base}<={strbound}: only strings have an upper bound')
    pkg, _, name = base.rpartition('/')
    if pkg and pkg != package:
        # another package's message: its IDL is found as <pkg>/msg/<Name>_.idl beside this
        # package's folder (--out <root>/<package>/msg), as rosidl lays them out
        includes.add(f'{pkg}/msg/{name}_.idl')
        return f'{pkg}::msg::dds_::{name}_'
    includes.add(f'{name}_.idl')
    return f'{package}::msg::dds_::{name}_'


def member(type_text, name, package, includes):
    m = TYPE.match(type_text)
    if not m:
        raise MsgError(f'cannot read type {type_text!r}')
    base = idl_base_type(m['base'], m['strbound'], package, includes)
    array = m['array']
    if array is None:
        return f'{base} {name}_;'
    if array == '':
        return f'sequence<{base}{" " if base.endswith(">") else ""}> {name}_;'
    if array.startswith('<='):
        return f'sequence<{base}, {array[2:]}> {name}_;'
    return f'{base} {name}_[{array}];'


def convert(path, package):
    type_name = path.stem
    includes = set()
    constants = []
    members = []
    for number, line in enumerate(path.read_text().splitlines(), 1):
        text = line.split('#', 1)[0].strip()
        if not text:
            continue
        m = FIELD.match(text)
        if not m:
            raise MsgError(f'{path}:{number}: cannot read {text!r}')
        try:
            rest = m['rest'].strip()
            if rest.startswith('='):  # a constant: it names no member and does not change the wire
                constants.append(f'const {idl_base_type(m["type"], None, package, set())} '
                                 f'{m["name"]}_ = {rest[1:].strip()};')
            else:  # a member; a default value (rest) does not change the wire either
                members.append(member(m['type'], m['name'], package, includes))
        except MsgError as e:
            raise MsgError(f'{path}:{number}: {e}') from None
    guard = f'__{package}__msg__{type_name}__idl__'
    out = [f'// {package}/msg/{type_name}.msg as ROS 2 makes it a DDS type (idl/ros2/msg_to_dds_idl.py)',
           f'#ifndef {guard}', f'#define {guard}', '']
    out += [f'#include "{include}"' for include in sorted(includes)]
    out += ['', f'module {package} {{', 'module msg {', 'module dds_ {', '']
    if constants:
        out += [f'module {type_name}_Constants {{'] + constants + ['};', '']
    out += [f'struct {type_name}_ {{'] + members + ['};', '',
            '};  // module dds_', '};  // module msg', f'}};  // module {package}', '', f'#endif  // {guard}', '']
    return type_name, '\n'.join(out)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('--package', required=True)
    parser.add_argument('--out', required=True, type=pathlib.Path)
    parser.add_argument('msg', nargs='+', type=pathlib.Path)
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    try:
        for path in args.msg:
            type_name, text = convert(path, args.package)
            (args.out / f'{type_name}_.idl').write_text(text)
    except MsgError as e:
        print(f'msg_to_dds_idl: {e}', file=sys.stderr)
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main())
