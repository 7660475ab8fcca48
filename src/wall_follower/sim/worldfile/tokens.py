"""A world file's words, numbers, strings and brackets, with its `include`s read in place."""
import os
import re
from collections import namedtuple

from .specs import WorldFileError


_Token = namedtuple('_Token', ['kind', 'text', 'path', 'line'])


_WORD_RE = re.compile(r'[A-Za-z][A-Za-z0-9.\-_\[\]]*')


_NUM_RE = re.compile(r'[+\-.0-9]+')


_PUNCT = '()[]'


def tokenize(path, include_stack=()):
    """Tokens of `path`, with `include "file"` expanded in place."""
    try:
        with open(path) as stream:
            text = stream.read()
    except (IOError, OSError, UnicodeDecodeError) as err:
        raise WorldFileError(path, 0, 'cannot read world file (%s)' % err)
    tokens = []
    line = 1
    pos = 0
    end = len(text)
    while pos < end:
        ch = text[pos]
        if ch == '\n':
            line += 1
            pos += 1
        elif ch.isspace():
            pos += 1
        elif ch == '#':
            newline = text.find('\n', pos)
            pos = end if newline < 0 else newline
        elif ch == '"':
            close = text.find('"', pos + 1)
            newline = text.find('\n', pos + 1)
            if close < 0 or (0 <= newline < close):
                raise WorldFileError(path, line, 'unterminated string')
            tokens.append(_Token('string', text[pos + 1:close], path, line))
            pos = close + 1
        elif ch in _PUNCT:
            tokens.append(_Token(ch, ch, path, line))
            pos += 1
        elif ch.isalpha():
            word = _WORD_RE.match(text, pos).group(0)
            tokens.append(_Token('word', word, path, line))
            pos += len(word)
        elif ch in '+-.' or ch.isdigit():
            number = _NUM_RE.match(text, pos).group(0)
            tokens.append(_Token('number', number, path, line))
            pos += len(number)
        else:
            raise WorldFileError(path, line, 'unexpected character %r' % ch)
    return _expand_includes(tokens, include_stack + (os.path.abspath(path),))


def _expand_includes(tokens, include_stack):
    out = []
    index = 0
    while index < len(tokens):
        token = tokens[index]
        if token.kind == 'word' and token.text == 'include':
            if index + 1 >= len(tokens) or tokens[index + 1].kind != 'string':
                raise WorldFileError(token.path, token.line, 'include needs a quoted file name')
            name = tokens[index + 1].text
            target = os.path.join(os.path.dirname(token.path), name)
            if not os.path.isfile(target):
                raise WorldFileError(token.path, token.line, 'include not found: "%s"' % name)
            if os.path.abspath(target) in include_stack:
                raise WorldFileError(token.path, token.line, 'recursive include of "%s"' % name)
            out.extend(tokenize(target, include_stack))
            index += 2
        else:
            out.append(token)
            index += 1
    return out
