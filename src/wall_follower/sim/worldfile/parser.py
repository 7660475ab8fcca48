"""A world file's tokens as written: `define`s and entities (`type ( ... )`) with their
properties, not yet interpreted."""
from collections import OrderedDict, namedtuple

from .specs import WorldFileError


Prop = namedtuple('Prop', ['values', 'path', 'line'])


class _Entity(object):
    """One `type ( ... )` block as written: properties and child entities."""

    def __init__(self, kind, path, line):
        self.kind = kind
        self.path = path
        self.line = line
        self.props = OrderedDict()
        self.children = []


class Parser(object):
    def __init__(self, tokens, path):
        self.tokens = tokens
        self.path = path
        self.index = 0
        self.defines = OrderedDict()   # name -> (parent, _Entity)

    def _peek(self, offset=0):
        i = self.index + offset
        return self.tokens[i] if i < len(self.tokens) else None

    def _last_position(self):
        if self.tokens:
            last = self.tokens[-1]
            return last.path, last.line
        return self.path, 1

    def _next(self, what):
        token = self._peek()
        if token is None:
            path, line = self._last_position()
            raise WorldFileError(path, line, 'unexpected end of file, expected %s' % what)
        self.index += 1
        return token

    def parse(self):
        root = _Entity('', self.path, 1)
        self._parse_body(root, top_level=True)
        return root

    def _parse_body(self, entity, top_level):
        while True:
            token = self._peek()
            if token is None:
                if not top_level:
                    raise WorldFileError(entity.path, entity.line,
                                         'unbalanced parenthesis: "%s (" is never closed'
                                         % entity.kind)
                return
            if token.kind == ')':
                if top_level:
                    raise WorldFileError(token.path, token.line, 'unbalanced parenthesis: '
                                         'unexpected ")"')
                self.index += 1
                return
            if token.kind != 'word':
                raise WorldFileError(token.path, token.line,
                                     'syntax error: unexpected %r' % token.text)
            if token.text == 'define':
                if not top_level:
                    raise WorldFileError(token.path, token.line,
                                         'define is only allowed at the top level')
                self._parse_define()
                continue
            following = self._peek(1)
            if following is not None and following.kind == '(':
                self.index += 2
                child = _Entity(token.text, token.path, token.line)
                self._parse_body(child, top_level=False)
                entity.children.append(child)
            else:
                self.index += 1
                entity.props[token.text] = Prop(self._parse_value(token), token.path, token.line)

    def _parse_define(self):
        define = self._next('define')
        name = self._next('a name after define')
        parent = self._next('a parent type after define %s' % name.text)
        opening = self._next('"(" after define %s %s' % (name.text, parent.text))
        if name.kind != 'word' or parent.kind != 'word' or opening.kind != '(':
            raise WorldFileError(define.path, define.line,
                                 'define needs the form: define NAME PARENT ( ... )')
        body = _Entity(parent.text, define.path, define.line)
        self._parse_body(body, top_level=False)
        self.defines[name.text] = (parent.text, body)

    def _parse_value(self, name):
        token = self._next('a value for "%s"' % name.text)
        if token.kind == '[':
            values = []
            while True:
                item = self._next('"]" closing the tuple of "%s"' % name.text)
                if item.kind == ']':
                    return values
                if item.kind == '[':
                    raise WorldFileError(item.path, item.line,
                                         'nested "[" in the tuple of "%s"' % name.text)
                if item.kind in '()':
                    raise WorldFileError(item.path, item.line,
                                         'unbalanced bracket: tuple of "%s" is not closed'
                                         % name.text)
                values.append(_scalar(item))
        if token.kind in ('string', 'number', 'word'):
            return [_scalar(token)]
        raise WorldFileError(token.path, token.line,
                             'syntax error: "%s" needs a value, found %r' % (name.text, token.text))


def _scalar(token):
    if token.kind == 'number':
        try:
            return float(token.text)
        except ValueError:
            raise WorldFileError(token.path, token.line, 'bad number %r' % token.text)
    return token.text
