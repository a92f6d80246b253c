//! The open documents' texts, as the client last sent them (full synchronisation).

use std::collections::HashMap;

use lsp_types::Uri;

#[derive(Debug, Default)]
pub struct Documents {
    texts: HashMap<Uri, String>,
}

impl Documents {
    pub fn open(&mut self, uri: Uri, text: String) {
        self.texts.insert(uri, text);
    }

    /// The whole new text: the server asks for full synchronisation, so the last change is
    /// the document.
    pub fn change(&mut self, uri: &Uri, changes: Vec<lsp_types::TextDocumentContentChangeEvent>) {
        if let (Some(text), Some(last)) = (self.texts.get_mut(uri), changes.into_iter().last()) {
            *text = last.text;
        }
    }

    pub fn close(&mut self, uri: &Uri) {
        self.texts.remove(uri);
    }

    pub fn get(&self, uri: &Uri) -> Option<&str> {
        self.texts.get(uri).map(String::as_str)
    }

    pub fn uris(&self) -> impl Iterator<Item = &Uri> {
        self.texts.keys()
    }
}
