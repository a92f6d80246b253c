"""`awl lsp` with a real client (pytest-lsp): diagnostics as the text changes, hover, go to
definition, completion and a quick fix. tests/lsp.rs runs it with AWL_BIN (the binary) and AWL_LSP_FOLDER (a folder
holding plant.awl, plant.seq and plant.toml)."""

import asyncio
import os
import pathlib

import pytest
import pytest_lsp
from lsprotocol import types
from pytest_lsp import ClientServerConfig, LanguageClient

FOLDER = pathlib.Path(os.environ["AWL_LSP_FOLDER"])
PROGRAM = FOLDER / "plant.awl"
URI = PROGRAM.as_uri()
TEXT = PROGRAM.read_text()


@pytest_lsp.fixture(config=ClientServerConfig(server_command=[os.environ["AWL_BIN"], "lsp"]))
async def client(lsp_client: LanguageClient):
    params = types.InitializeParams(
        capabilities=types.ClientCapabilities(), root_uri=FOLDER.as_uri()
    )
    await lsp_client.initialize_session(params)
    yield
    await lsp_client.shutdown_session()


def at(line, character):
    return types.TextDocumentPositionParams(
        text_document=types.TextDocumentIdentifier(uri=URI),
        position=types.Position(line=line, character=character),
    )


async def diagnostics_of_program(client):
    """The next diagnostics published for the program (the assignment list has its own)."""
    while True:
        params = await asyncio.wait_for(
            client.wait_for_notification(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS), 20
        )
        if params.uri == URI:
            return params.diagnostics


async def open_text(client, text):
    client.text_document_did_open(
        types.DidOpenTextDocumentParams(
            text_document=types.TextDocumentItem(uri=URI, language_id="awl", version=1, text=text)
        )
    )
    return await diagnostics_of_program(client)


@pytest.mark.asyncio
async def test_errors_arrive_and_clear_when_fixed(client: LanguageClient):
    found = await open_text(client, TEXT.replace("      R  =AUS", "      XYZ  =AUS"))
    assert found, "the unknown operation is reported"
    error = found[0]
    assert error.severity == types.DiagnosticSeverity.Error
    assert str(error.code).startswith("awl::")
    assert error.code_description.href.startswith("file://"), "the code links to its page"
    assert error.range.start.line == 14
    client.text_document_did_change(
        types.DidChangeTextDocumentParams(
            text_document=types.VersionedTextDocumentIdentifier(uri=URI, version=2),
            content_changes=[types.TextDocumentContentChangeWholeDocument(text=TEXT)],
        )
    )
    assert not await diagnostics_of_program(client), "the fix clears them"


@pytest.mark.asyncio
async def test_hover_on_an_operation_and_a_symbol(client: LanguageClient):
    await open_text(client, TEXT)
    operation = await client.text_document_hover_async(types.HoverParams(**vars_of(at(1, 6))))
    assert "`U`" in operation.contents.value
    assert "s5-115u" in operation.contents.value
    assert "| reads | - | - | - | x | x | x |" in operation.contents.value, "the status bits"
    symbol = await client.text_document_hover_async(types.HoverParams(**vars_of(at(1, 13))))
    assert "I 0.0" in symbol.contents.value
    assert "start button" in symbol.contents.value


@pytest.mark.asyncio
async def test_go_to_a_label_and_a_block(client: LanguageClient):
    await open_text(client, TEXT)
    label = await client.text_document_definition_async(
        types.DefinitionParams(**vars_of(at(13, 10)))
    )
    assert label.range.start.line == 16
    block = await client.text_document_definition_async(
        types.DefinitionParams(**vars_of(at(2, 12)))
    )
    assert block.range.start.line == 8


@pytest.mark.asyncio
async def test_complete_a_symbol(client: LanguageClient):
    await open_text(client, TEXT.replace("-START", "-ST"))
    found = await client.text_document_completion_async(
        types.CompletionParams(**vars_of(at(1, 15)))
    )
    items = found.items if isinstance(found, types.CompletionList) else found
    start = next(item for item in items if item.label == "-START")
    assert start.kind == types.CompletionItemKind.Constant
    assert "I 0.0" in start.detail


@pytest.mark.asyncio
async def test_a_quick_fix_separates_operation_and_operand(client: LanguageClient):
    broken = TEXT.replace("      R  =AUS", "      L KF +5\n      T1")
    found = await open_text(client, broken)
    error = next(d for d in found if d.range.start.line == 15)
    actions = await client.text_document_code_action_async(
        types.CodeActionParams(
            text_document=types.TextDocumentIdentifier(uri=URI),
            range=error.range,
            context=types.CodeActionContext(diagnostics=[error]),
        )
    )
    fix = actions[0]
    assert fix.kind == types.CodeActionKind.QuickFix
    assert applied(broken, fix.edit.changes[URI]).splitlines()[15] == "      T 1"


def applied(text, edits):
    """`text` with edits that each stay on one line, made from the last to the first."""
    lines = text.split("\n")
    last_first = sorted(
        edits, key=lambda e: (e.range.start.line, e.range.start.character), reverse=True
    )
    for edit in last_first:
        start, end = edit.range.start, edit.range.end
        assert start.line == end.line
        line = lines[start.line]
        lines[start.line] = line[: start.character] + edit.new_text + line[end.character :]
    return "\n".join(lines)


def vars_of(position):
    return {"text_document": position.text_document, "position": position.position}
