"""Parameters with a fixed set of choices: refused outside them, and an enum of them in the
dynamic_reconfigure config generated from the table (what rqt_reconfigure lists and
`dynparam set` takes by name)."""
import ast
import sys

import pytest
from dynamic_reconfigure.encoding import extract_params
from dynamic_reconfigure.parameter_generator_catkin import ParameterGenerator

from wall_follower.params import (Parameter as P, ParameterError, Section, checked, declare,
                                  parameters)
from wall_follower.params.camera import line_follower
from wall_follower.params.sim import stage_sim

MODES = (Section('mode', (P('mode', 'fast', 'how to go', choices=('fast', 'slow')),
                          P('speed', 0.1, 'how fast [m/s]', 0.0, 1.0))),)


def enums(description):
    """name -> the values of its enum, of each parameter of a config description."""
    return {p['name']: [c['value'] for c in ast.literal_eval(p['edit_method'])['enum']]
            for p in extract_params(description) if p['edit_method']}


@pytest.fixture
def generator(monkeypatch, tmp_path):
    """A ParameterGenerator as catkin runs a cfg script (it reads its paths from argv)."""
    monkeypatch.setattr(sys, 'argv', ['x.cfg'] + [str(tmp_path)] * 4)
    return ParameterGenerator()


def test_a_value_outside_the_choices_is_refused_naming_them():
    with pytest.raises(ParameterError) as refused:
        checked(line_follower.TABLE, {'controller': 'bogus'})
    assert refused.value.problems == ["controller must be one of pursuit, pixel_p, not 'bogus'"]
    assert checked(line_follower.TABLE, {'controller': 'pixel_p'})['controller'] == 'pixel_p'
    with pytest.raises(ParameterError):
        checked(stage_sim.TABLE, {'laser_profile': 'lds03'})


def test_the_default_must_be_a_choice():
    with pytest.raises(ValueError):
        P('mode', 'medium', 'how to go', choices=('fast', 'slow'))


def test_choices_are_declared_as_an_enum(generator):
    declare(generator, MODES)
    assert enums(generator.group.to_dict()) == {'mode': ['fast', 'slow']}
    assert [c['name'] for c in generator.constants] == ['fast', 'slow']


@pytest.mark.parametrize('choices', [('fast', 'two words'), ('1st', '2nd')])
def test_choices_that_cannot_name_a_constant_are_refused(generator, choices):
    table = (Section('mode', (P('mode', choices[0], 'how', choices=choices),)),)
    with pytest.raises(ValueError):
        declare(generator, table)


def test_choices_named_twice_in_a_table_are_refused(generator):
    table = (Section('modes', (P('a', 'on', 'a', choices=('on', 'off')),
                               P('b', 'on', 'b', choices=('on', 'off')))),)
    with pytest.raises(ValueError):
        declare(generator, table)


def test_the_generated_line_follower_config_offers_the_choices():
    from wall_follower.cfg import LineFollowerConfig
    assert enums(LineFollowerConfig.config_description) == {
        p.name: list(p.choices) for p in parameters(line_follower.TABLE) if p.choices}
    assert enums(LineFollowerConfig.config_description)['controller'] == ['pursuit', 'pixel_p']
