"""The Design's vocabulary (contactsep.model.fields): the field table is
the Design's, its words are the ones the Design takes, and a chatter
setting is named there but read by contactsep.chatter.settings."""

from __future__ import annotations

import dataclasses
import re

import pytest

from contactsep.chatter import settings
from contactsep.errors import InputError
from contactsep.model import Design, fields, thesis_design

DESIGN_FIELDS = [f.name for f in dataclasses.fields(Design)]


def test_the_field_table_is_the_designs():
    assert set(fields.FIELDS) == set(DESIGN_FIELDS)
    # each unit as help(Design) states it, a table written apart
    doc = Design.__doc__
    for field in DESIGN_FIELDS:
        unit = fields.unit(field)
        line = next(line for line in doc.splitlines()
                    if re.match(rf"\s+([\w, ]+, )?{field}(,[\w, ]+)? : ",
                                line))
        stated = line.split(" : ")[1].split(" or ")[0].strip()
        assert stated == (unit or stated), (field, stated, unit)


def test_every_word_of_a_field_is_one_the_design_takes():
    # a contact point inside the span, so that every end condition fits
    inside = {"x1": 9.5, "x3": 9.5}
    for field, words in fields.CHOICES.items():
        for word in words:
            design = thesis_design(**inside, **{field: word})
            assert getattr(design, field) == word
    with pytest.raises(InputError):
        thesis_design(impact_velocity="thesis")


@pytest.mark.parametrize("name, column", [
    ("h2", "d_in"), ("e", "e"), ("gamma2", "gamma2_lb_in3"),
    ("kr1", "kr1_lb_in_rad"), ("preload", "preload_lb"),
    ("alpha", "alpha_s_per_in"), ("damping", "damping")])
def test_column_names_are_the_documented_keys(name, column):
    # docs/names-and-units.md, "The names"; both directions
    assert fields.column_name(name) == column
    assert fields.field_name(column, settings=True) == name


def test_a_setting_is_named_as_a_field_is_but_refused_as_one():
    with pytest.raises(InputError, match=r"^--set preload: a setting of the "
                       r"chatter simulation, not a design field: give it "
                       r"as --preload"):
        fields.field_name("preload", "--set preload")
    with pytest.raises(InputError, match="not a design field"):
        fields.field_name("h9")


def test_settings_values_are_read_by_the_chatter_layer():
    # 25.4 mm is one inch by definition; a field passes through
    assert settings.parse_value("h2", "25.4mm", "--d") == 1.0
    assert settings.parse_value("damping", " flores ", "--damping") == \
        "flores"
    assert settings.CHOICES["damping"] == settings.DAMPINGS
    assert settings.CHOICES["contact"] == settings.CONTACTS
    with pytest.raises(InputError, match=r"^--preload: found '-1', "
                       r"expected a force >= 0 lb$"):
        settings.parse_value("preload", "-1", "--preload")
    with pytest.raises(InputError, match=r"expected a window > 0 and at "
                       r"most 10 s"):
        settings.parse_value("t_end", "11", "--t-end")
    # the model's reader is the Design's: a setting is not its to read
    with pytest.raises(KeyError):
        fields.parse_value("preload", "0.2", "--preload")
