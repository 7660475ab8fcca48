"""The benchmarks' and the grader's tables: a figure to a cell, rows to a Markdown table."""


def fmt(value, spec):
    """A table cell; '-' where a figure is missing; a figure kept as text (a record's 'inf'
    or 'nan', which JSON cannot hold as numbers) as it is."""
    if value is None or value != value:
        return '-'
    if isinstance(value, str):
        return value
    return format(value, spec)


def print_table(header, rows):
    widths = [max(len(str(cell)) for cell in column) for column in zip(header, *rows)]

    def line(cells):
        return '| ' + ' | '.join(str(c).ljust(w) for c, w in zip(cells, widths)) + ' |'
    print(line(header))
    print('|' + '|'.join('-' * (w + 2) for w in widths) + '|')
    for row in rows:
        print(line(row))
