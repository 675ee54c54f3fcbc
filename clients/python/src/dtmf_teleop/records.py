"""Protobuf messages as plain dicts: every field present, absent optional values as None,
64-bit integers as ints (protobuf's own json_format would make them strings)."""

from __future__ import annotations

from typing import Any

from google.protobuf.descriptor import FieldDescriptor
from google.protobuf.message import Message


def message_to_dict(message: Message) -> dict[str, Any]:
    result: dict[str, Any] = {}
    for f in message.DESCRIPTOR.fields:
        value = getattr(message, f.name)
        if f.label == FieldDescriptor.LABEL_REPEATED:
            result[f.name] = [message_to_dict(v) if f.message_type else v for v in value]
        elif f.message_type:
            result[f.name] = message_to_dict(value) if message.HasField(f.name) else None
        elif f.has_presence and not message.HasField(f.name):  # proto3 optional, oneof members
            result[f.name] = None
        elif f.enum_type:
            result[f.name] = f.enum_type.values_by_number[value].name
        else:
            result[f.name] = value
    return result
