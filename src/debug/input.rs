//! Where the debugger's commands come from: a line-editing prompt on a terminal, or a script
//! (`--commands FILE`, or standard input that is no terminal) whose lines are echoed.

use std::collections::VecDeque;
use std::io::BufRead;

#[cfg(not(target_arch = "wasm32"))]
use rustyline::DefaultEditor;
#[cfg(not(target_arch = "wasm32"))]
use rustyline::error::ReadlineError;

pub const PROMPT: &str = "(awl) ";

pub enum Input {
    /// A terminal's line editor (not in a browser).
    #[cfg(not(target_arch = "wasm32"))]
    Prompt(Box<DefaultEditor>),
    Script(VecDeque<String>),
}

/// One line from the input.
pub enum Line {
    Text(String),
    /// Ctrl-C at the prompt: nothing to do, prompt again.
    Cancelled,
    End,
}

impl Input {
    /// The prompt, or `None` when no line editor can run here (then standard input is read as a
    /// script).
    #[cfg(not(target_arch = "wasm32"))]
    pub fn prompt() -> Option<Input> {
        DefaultEditor::new()
            .ok()
            .map(|editor| Input::Prompt(Box::new(editor)))
    }

    pub fn script(text: &str) -> Input {
        Input::Script(text.lines().map(str::to_string).collect())
    }

    /// Standard input, read to its end, as a script.
    pub fn stdin() -> Input {
        let lines = std::io::stdin().lock().lines().map_while(Result::ok);
        Input::Script(lines.collect())
    }

    pub fn is_script(&self) -> bool {
        matches!(self, Input::Script(_))
    }

    /// The next line; a script's line is echoed after the prompt, as if typed.
    pub fn next_line(&mut self, echo: &mut dyn FnMut(&str)) -> Line {
        match self {
            #[cfg(not(target_arch = "wasm32"))]
            Input::Prompt(editor) => match editor.readline(PROMPT) {
                Ok(line) => {
                    if !line.trim().is_empty() {
                        let _ = editor.add_history_entry(line.as_str());
                    }
                    Line::Text(line)
                }
                Err(ReadlineError::Interrupted) => Line::Cancelled,
                Err(_) => Line::End,
            },
            Input::Script(lines) => match lines.pop_front() {
                Some(line) => {
                    echo(&format!("{PROMPT}{line}\n"));
                    Line::Text(line)
                }
                None => Line::End,
            },
        }
    }
}
