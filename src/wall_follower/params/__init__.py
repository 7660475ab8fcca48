"""Every node's parameters, declared once: name, default, meaning and range.

Each node has one table, in the subpackage of its job as nodes/ has them
(course/wall_following.py, camera/line_follower.py, ...), a tuple of
Sections of Parameters. That table is the single source of the
node's defaults, their units and their meanings (the sections every
driving node shares, its loop's and its clamp's, come from driving.py);
everything else derives from it:

- cfg/<Node>.cfg, dynamic_reconfigure's generator script, imports the
  table and declares each parameter from it (declare() below); catkin then
  generates wall_follower.cfg.<Node>Config, which the node's
  dynamic_reconfigure server, `dynparam` and rqt_reconfigure read;
- the pure-logic classes (FollowerParams, WallFinder, LapRecorder, the
  exercises' behaviours) take their defaults from the same table through
  defaults() and checked(), so that unit tests and the simulator's closed
  loops build them with no ROS master, no catkin build and no
  dynamic_reconfigure installed;
- config/*.yaml and the launch files hold only the values that differ
  from these defaults, and test/unit/test_parameter_sources.py holds them,
  the README's tables and the generated modules to this table.

Why a table that the .cfg imports, rather than defaults read back from the
generated module: the generated module exists only after a catkin build
and imports dynamic_reconfigure, which the pure logic must not need; a
plain table serves the build and the logic alike.

Units are SI as REP 103 has them: metres, seconds, radians (and m/s,
rad/s). Angles are declared in radians even where a round number of
degrees was meant (math.radians(30.0)), so that the value is exact.
"""
import collections
import numbers


_FIELDS = 'name default description minimum maximum choices'


class Parameter(collections.namedtuple('Parameter', _FIELDS)):
    """One tunable value. The default fixes its type: bool, int, float or str, or
    dict for a structure read from YAML (dynamic_reconfigure has no type for
    one: only a node without live tuning can declare it).

    description: what it means, with its unit in brackets; it is what
    rqt_reconfigure shows. minimum, maximum: the range a number must lie
    in (None: unbounded on that side). choices: the only values it may take,
    when there is a fixed set of them (the default among them); declare()
    makes them an enum, which rqt_reconfigure offers as a list.
    """

    __slots__ = ()

    def __new__(cls, name, default, description, minimum=None, maximum=None, choices=()):
        choices = tuple(choices)
        if choices and default not in choices:
            raise ValueError('%s: the default %r is not one of its choices %s'
                             % (name, default, ', '.join(map(str, choices))))
        return super(Parameter, cls).__new__(cls, name, default, description, minimum, maximum,
                                             choices)

    @property
    def kind(self):
        """Its dynamic_reconfigure type: 'bool', 'int', 'double' or 'str' (or 'dict')."""
        return _kind(self.default)

    def check(self, value):
        """value converted to this parameter's type; ValueError saying why it cannot be."""
        kind = self.kind
        if kind == 'bool':
            ok = isinstance(value, bool)
        elif kind == 'int':
            ok = (isinstance(value, numbers.Integral) and not isinstance(value, bool)) or (
                isinstance(value, float) and value.is_integer())
        elif kind == 'double':
            ok = isinstance(value, numbers.Real) and not isinstance(value, bool)
        elif kind == 'str':
            ok = isinstance(value, str)
        else:
            ok = isinstance(value, dict)
        if not ok:
            raise ValueError('%s must be %s, not %r (%s)' % (
                self.name, _KIND_NAMES[kind], value, type(value).__name__))
        value = type(self.default)(value)
        if self.minimum is not None and value < self.minimum:
            raise ValueError('%s must be at least %r, not %r' % (self.name, self.minimum, value))
        if self.maximum is not None and value > self.maximum:
            raise ValueError('%s must be at most %r, not %r' % (self.name, self.maximum, value))
        if self.choices and value not in self.choices:
            raise ValueError('%s must be one of %s, not %r' % (
                self.name, ', '.join(map(str, self.choices)), value))
        return value


_KIND_NAMES = {'bool': 'true or false', 'int': 'a whole number', 'double': 'a number',
               'str': 'a string', 'dict': 'a mapping'}


def _kind(default):
    if isinstance(default, bool):
        return 'bool'
    if isinstance(default, int):
        return 'int'
    if isinstance(default, float):
        return 'double'
    if isinstance(default, str):
        return 'str'
    if isinstance(default, dict):
        return 'dict'
    raise TypeError('a parameter default must be bool, int, float, str or dict, not %r'
                    % (default,))


Section = collections.namedtuple('Section', 'name parameters')
"""A group of parameters (a box in rqt_reconfigure); name is an identifier."""


class ParameterError(ValueError):
    """Parameters that cannot be used; problems holds one sentence for each."""

    def __init__(self, problems):
        ValueError.__init__(self, '; '.join(problems))
        self.problems = list(problems)

    def __reduce__(self):
        """Rebuilt from the problems, not from the joined message.

        An error sent to another process (multiprocessing, a pool of
        workers) is pickled, and by default rebuilt from its args: the
        joined message taken for the list of problems reads one letter per
        problem.
        """
        return type(self), (self.problems,)


def parameters(table):
    """Every Parameter of a table, in order."""
    return [parameter for section in table for parameter in section.parameters]


def names(table):
    return [parameter.name for parameter in parameters(table)]


def defaults(table):
    """name -> default of every parameter of a table."""
    return dict((parameter.name, parameter.default) for parameter in parameters(table))


def pick(values, table):
    """The entries of values (name -> value) that are parameters of table."""
    return dict((name, values[name]) for name in names(table) if name in values)


def checked(table, values, rules=()):
    """The defaults of table, overridden by values (name -> value), each checked.

    Raises ParameterError naming every unknown name, every value of the
    wrong type and every one out of range, so that a misspelling or a
    slip in a configuration file is reported instead of leaving a default
    in force. rules: what values must satisfy together, which no range
    can say (functions of name -> value answering a sentence saying what
    is wrong, or None); checked once each value is good.
    """
    declared = dict((parameter.name, parameter) for parameter in parameters(table))
    result = defaults(table)
    problems = ['unknown parameter %s' % name for name in sorted(set(values) - set(declared))]
    for name, value in values.items():
        if name in declared:
            try:
                result[name] = declared[name].check(value)
            except ValueError as error:
                problems.append(str(error))
    if not problems:
        problems = [problem for problem in (rule(result) for rule in rules) if problem]
    if problems:
        raise ParameterError(problems)
    return result


def declare(generator, table):
    """Add every parameter of a table to a dynamic_reconfigure ParameterGenerator.

    Called by the cfg/*.cfg scripts; one group per section, all at level 0
    (a node applies every change at its next scan). A parameter with
    choices gets an enum of them as its edit_method: rqt_reconfigure offers
    the list, and `dynparam set` takes a choice by its name in any case.
    dynamic_reconfigure itself checks no enum value (its client passes any
    string on), so the node's own check (Parameter.check) is what refuses
    one that is not a choice.
    """
    constants = [str(choice) for p in parameters(table) for choice in p.choices]
    # Generated as <Config>_<choice> in the Python module and the C++ header.
    unusable = sorted(set(name for name in constants
                          if not name.isidentifier() or constants.count(name) > 1))
    if unusable:
        raise ValueError('choices that cannot name an enum constant (not a name, or twice '
                         'in the table): %s' % ', '.join(unusable))
    for section in table:
        group = generator.add_group(section.name)
        for p in section.parameters:
            group.add(p.name, p.kind, 0, p.description, p.default, p.minimum, p.maximum,
                      edit_method=_enum(generator, p) if p.choices else '')


def _enum(generator, parameter):
    """The edit_method of a parameter with choices: an enum with a constant for each."""
    return generator.enum([generator.const(str(choice), parameter.kind, choice,
                                           '%s %s' % (parameter.name, choice))
                           for choice in parameter.choices],
                          'the choices of %s' % parameter.name)
