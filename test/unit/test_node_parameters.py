"""NodeParameters at start and under reconfiguration, on a stand-in parameter server."""
import pytest

from wall_follower.nodes.shared import parameters
from wall_follower.params import Parameter, Section

TABLE = (Section('node', (Parameter('target_distance', 0.25, 'wanted distance [m]', 0.1, 1.0),
                          Parameter('wall_min_points', 6, 'fewest hits', 2, 100),
                          Parameter('find_wall', True, 'call find_wall first'))),)


def _logger(level):
    def log(self, text, *args):
        self.logs.append((level, text % args))
    return log


class FakeRospy(object):
    """The few rospy calls NodeParameters makes, against a dict of private parameters."""

    def __init__(self, private):
        self.private = dict(private)
        self.logs = []

    def get_param(self, name, default=None):
        assert name == '~'
        return dict(self.private)

    def set_param(self, name, value):
        self.private[name.lstrip('~')] = value

    @staticmethod
    def get_name():
        return '/node'

    loginfo, logwarn = _logger('info'), _logger('warn')
    logerr, logfatal = _logger('error'), _logger('fatal')

    class ServiceException(Exception):
        """What a service handler raises to fail the call (rospy.ServiceException)."""


@pytest.fixture
def server(monkeypatch):
    def start(private):
        fake = FakeRospy(private)
        monkeypatch.setattr(parameters, 'rospy', fake)
        return fake
    return start


def test_values_given_are_used_and_written_back_in_their_type(server):
    fake = server({'target_distance': 0.3, 'wall_min_points': 7.0})
    params = parameters.NodeParameters(TABLE)
    assert params.snapshot() == {'target_distance': 0.3, 'wall_min_points': 7, 'find_wall': True}
    assert type(fake.private['wall_min_points']) is int
    assert not fake.logs


def test_an_unknown_key_is_named_in_a_warning_with_the_known_ones(server):
    fake = server({'target_distanse': 0.3})
    params = parameters.NodeParameters(TABLE)
    assert params.snapshot()['target_distance'] == 0.25
    assert [level for level, _ in fake.logs] == ['warn']
    assert '~target_distanse' in fake.logs[0][1]
    # No dynamic_reconfigure server to ask: the warning names them.
    assert '~target_distance, ~wall_min_points, ~find_wall are the known ones' in fake.logs[0][1]


@pytest.mark.parametrize('name, value, says', [
    ('target_distance', 'far', '~target_distance must be a number'),
    ('find_wall', 'yes', '~find_wall must be true or false'),
    ('target_distance', 5.0, '~target_distance must be at most 1.0'),
])
def test_a_bad_value_stops_the_node_with_an_error_naming_it(server, name, value, says):
    fake = server({name: value})
    with pytest.raises(SystemExit) as stop:
        parameters.NodeParameters(TABLE)
    assert stop.value.code == 1
    assert fake.logs[-1][0] == 'fatal' and says in fake.logs[-1][1]


def test_a_change_is_handed_over_once(server):
    server({})
    params = parameters.NodeParameters(TABLE)
    assert params.take_update() is None
    config = {'target_distance': 0.22, 'wall_min_points': 6, 'find_wall': True, 'groups': {}}
    assert params._on_reconfigure(config, 0) is config
    assert params.take_update()['target_distance'] == 0.22
    assert params.take_update() is None
    params._on_reconfigure(dict(config), 0)   # the same values again: nothing new
    assert params.take_update() is None


def test_a_change_that_cannot_be_used_fails_the_call_and_the_old_values_stay(server):
    fake = server({})
    params = parameters.NodeParameters(TABLE)
    config = {'target_distance': 'far', 'wall_min_points': 6, 'find_wall': True, 'groups': {}}
    # The set_parameters call fails, so that its client (dynparam) is told, not only the log.
    with pytest.raises(FakeRospy.ServiceException, match='refused: target_distance'):
        params._on_reconfigure(config, 0)
    assert params.take_update() is None
    assert params.snapshot()['target_distance'] == 0.25
    assert fake.logs[-1][0] == 'error' and 'target_distance' in fake.logs[-1][1]


def _near_unless_found(values):
    if not values['find_wall'] and values['target_distance'] > 0.5:
        return 'target_distance must be at most 0.5 without find_wall'
    return None


def test_values_that_break_a_rule_stop_the_node_or_are_refused_live(server):
    fake = server({'target_distance': 0.7})
    params = parameters.NodeParameters(TABLE, rules=(_near_unless_found,))
    config = {'target_distance': 0.7, 'wall_min_points': 6, 'find_wall': False, 'groups': {}}
    with pytest.raises(FakeRospy.ServiceException, match='at most 0.5 without find_wall'):
        params._on_reconfigure(config, 0)
    assert params.take_update() is None
    assert params.snapshot()['find_wall'] is True
    assert fake.logs[-1][0] == 'error' and 'at most 0.5 without find_wall' in fake.logs[-1][1]
    fake = server({'target_distance': 0.7, 'find_wall': False})
    with pytest.raises(SystemExit):
        parameters.NodeParameters(TABLE, rules=(_near_unless_found,))
    assert fake.logs[-1] == ('fatal', '/node: cannot start: ~target_distance must be at most 0.5 '
                             'without find_wall (check the launch file and config/*.yaml)')


def test_a_change_to_a_value_read_at_start_is_refused_and_the_rest_applied(server):
    fake = server({})
    params = parameters.NodeParameters(TABLE, read_at_start=('wall_min_points',))
    config = {'target_distance': 0.22, 'wall_min_points': 9, 'find_wall': True, 'groups': {}}
    answer = params._on_reconfigure(config, 0)
    assert answer['wall_min_points'] == 6 and answer['target_distance'] == 0.22
    assert params.take_update() == {'target_distance': 0.22, 'wall_min_points': 6,
                                    'find_wall': True}
    assert [level for level, _ in fake.logs] == ['warn', 'info']
    assert '~wall_min_points read at start only; kept as 6' in fake.logs[0][1]


def test_a_found_value_is_looked_for_only_once_the_given_ones_pass(server):
    """A bad given value stops the node at once, before the (maybe long) wait of a finder."""
    asked = []

    def find():
        asked.append(True)
        return 0.3

    server({'wall_min_points': 1000})
    with pytest.raises(SystemExit):
        parameters.NodeParameters(TABLE, found={'target_distance': find})
    assert not asked
    server({'wall_min_points': 7})
    params = parameters.NodeParameters(TABLE, found={'target_distance': find})
    assert asked and params.snapshot()['target_distance'] == 0.3
